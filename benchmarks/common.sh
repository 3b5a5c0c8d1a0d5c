# Sourced by the end-to-end benchmark scripts: checks the CLI is built, installs jq if
# missing, and makes a work folder removed on exit. Sets: pqlayout, work. Needs: build, name.
pqlayout="$build/cli/pqlayout"
[[ -x "$pqlayout" ]] || { echo "$name: $pqlayout not found; build first (bash scripts/build.sh)" >&2; exit 2; }
if ! command -v jq >/dev/null; then
  echo "$name: installing jq" >&2
  apt-get install -y -qq jq >/dev/null
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
