# Sourced by the ensemble scripts (layout_ensemble.sh, stiffness_ensemble.sh) after their
# arguments: builds pqlayout unless --bin named one, checks for jq and makes a work folder
# removed on exit. Needs: name, bin. Sets: bin, tmp.
if [ -z "$bin" ]; then
  bash scripts/build.sh pqlayout > /dev/null
  bin=build/cli/pqlayout
fi
command -v jq > /dev/null || { echo "$name: needs jq (apt-get install jq)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
