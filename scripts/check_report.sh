#!/usr/bin/env bash
# Opens a pqlayout report.html in headless Chromium and fails (exit 1) if a figure is missing
# or empty, if the 3D view is blank or does not turn, or if a screenshot of the whole page
# is blank.
#
#   scripts/check_report.sh REPORT.html [SCREENSHOT.png]
#
# How: report.html carries a small inline script that, once the page has loaded, measures
# every <figure data-figure=...>: rendered size, number of drawn SVG elements, and — the SVG
# rasterised onto a canvas — the fraction of non-white pixels ("ink") and the number of
# distinct colours inside the plot rectangle (data-plot), i.e. without the title, colour bar
# and scale bar. Chromium's --dump-dom prints the DOM after that script ran; this script
# reads the measurements and applies the thresholds below. A figure that is missing, holds
# no SVG, fails to rasterise, is smaller than MIN_WIDTH × MIN_HEIGHT px on the page or has
# less than MIN_INK of its plot drawn fails. Then the page is screenshotted at its full
# height (window 1280 px wide) and the PNG itself is loaded back into Chromium (as a data:
# URL, so the canvas can read it) to check it has at least MIN_PAGE_INK non-white pixels
# and MIN_PAGE_COLOURS distinct colours.
#
# The 3D view (report/report_view3d.h), where the page has one, measures itself the same
# way once drawn — its WebGL canvas copied onto a 2D canvas: non-white fraction ("ink") and
# distinct colours — then turns its camera by 30° about the vertical, draws again and counts
# the pixels that changed ("rotated"), and writes the numbers into the section's data-check.
# It fails here if the check did not run, WebGL was missing, the script failed, or the view
# is blank (ink < MIN_VIEW_INK or colours < MIN_VIEW_COLOURS) or did not turn (rotated <
# MIN_VIEW_ROTATED); a page without a 3D view (a run stopped before extract) only says so.
# Headless, with --disable-gpu and on machines without one, WebGL runs on SwiftShader,
# Chromium's CPU renderer (ANGLE on SwiftShader's Vulkan). Debian's Chromium 156 still falls
# back to it by itself, but Chromium is retiring that automatic fallback, so the flags ask
# for it: --use-angle=swiftshader --enable-unsafe-swiftshader ("unsafe" for arbitrary web
# content; we open our own page only). The same renderer on every machine, GPU or not.
# (--use-gl=swiftshader, the older spelling, leaves Chromium 156 with no WebGL at all.)
#
# Exit 0 if all is well, 1 if a check fails, 2 on bad usage or if Chromium cannot be run.
# CHROMIUM overrides the browser binary; SCREENSHOT_SCALE (default 1) scales the
# screenshot's pixels (0.5: half size, for docs).
set -euo pipefail

MIN_WIDTH=200        # rendered figure size on the page, CSS px
MIN_HEIGHT=150
MIN_MARKS=5          # drawn SVG elements (path, rect, circle, use, ...)
MIN_INK=0.02         # fraction of the plot rectangle that is not white
MIN_PAGE_INK=0.05    # fraction of the screenshot that is not white
MIN_PAGE_COLOURS=50  # distinct colours (4 bits per channel) in the screenshot
MIN_VIEW_INK=0.05    # 3D view: fraction of the canvas that is not white
MIN_VIEW_COLOURS=8   # 3D view: distinct colours (4 bits per channel)
MIN_VIEW_ROTATED=0.02  # 3D view: fraction of its pixels that a 30° turn of the camera changes
WINDOW_WIDTH=1280

if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $0 REPORT.html [SCREENSHOT.png]" >&2
  exit 2
fi
[ -f "$1" ] || { echo "$1: no such file" >&2; exit 2; }
report=$(realpath "$1")
chromium=${CHROMIUM:-chromium}
command -v "$chromium" >/dev/null || { echo "$chromium: not found (Debian package chromium)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
shot=${2:-$tmp/screenshot.png}
flags=(--headless --no-sandbox --disable-gpu --use-angle=swiftshader --enable-unsafe-swiftshader
       --no-first-run --disable-background-networking
       --user-data-dir="$tmp/profile" --virtual-time-budget=5000 --window-size=$WINDOW_WIDTH,1000)

# Chromium prints its DOM on stdout; its own log lines (dbus, ...) go to stderr.
dump_dom() {
  "$chromium" "${flags[@]}" --dump-dom "$1" 2>"$tmp/chromium.log" || {
    echo "chromium failed on $1:" >&2
    tail -5 "$tmp/chromium.log" >&2
    exit 2
  }
}

dump_dom "file://$report" > "$tmp/dom.html"
checked=$(grep -o 'data-checked="[0-9]*"' "$tmp/dom.html" | head -1 | grep -o '[0-9]*' || true)
if [ -z "$checked" ]; then
  echo "FAIL $1: the page's figure check did not finish (not a pqlayout report, scripts off, or over the 5 s virtual-time budget)"
  exit 1
fi
failed=0
if [ "$checked" -eq 0 ]; then
  echo "FAIL $1: no figures"
  failed=1
fi
# One line per figure: NAME CHECK (the attributes are written by the page in this order).
grep -o '<figure data-figure="[^"]*"[^>]*data-check="[^"]*"' "$tmp/dom.html" |
  sed -E 's/<figure data-figure="([^"]*)".*data-check="([^"]*)"/\1 \2/' > "$tmp/figures.txt"
if [ "$(wc -l < "$tmp/figures.txt")" -ne "$checked" ]; then
  echo "FAIL $1: $checked figures but $(wc -l < "$tmp/figures.txt") measurements"
  failed=1
fi
while read -r name check; do
  verdict=$(awk -v c="$check" -v mw=$MIN_WIDTH -v mh=$MIN_HEIGHT -v mm=$MIN_MARKS -v mi=$MIN_INK '
    BEGIN {
      n = split(c, kv, " ");
      for (i = 1; i <= n; ++i) { split(kv[i], p, "="); v[p[1]] = p[2]; }
      if (!("ink" in v)) { print "missing or unreadable (" c ")"; exit; }
      if (v["w"] < mw || v["h"] < mh) { print "too small: " v["w"] "x" v["h"] " px"; exit; }
      if (v["marks"] < mm) { print "empty: " v["marks"] " drawn elements"; exit; }
      if (v["ink"] < mi) { print "empty plot: ink " v["ink"] " < " mi; exit; }
      print "ok";
    }')
  if [ "$verdict" = ok ]; then
    echo "ok   $name ($check)"
  else
    echo "FAIL $name: $verdict"
    failed=1
  fi
done < "$tmp/figures.txt"

# The 3D view's self-check (data-check="w=.. h=.. faces=.. ink=.. colours=.. rotated=..").
view=$(grep -o '<section id="view3d"[^>]*>' "$tmp/dom.html" | head -1 || true)
if [ -z "$view" ]; then
  echo "--   3D view: none in this report"
else
  check=$(grep -o 'data-check="[^"]*"' <<< "$view" | sed -E 's/data-check="(.*)"/\1/' || true)
  verdict=$(awk -v c="$check" -v mw=$MIN_WIDTH -v mh=$MIN_HEIGHT -v mi=$MIN_VIEW_INK -v mc=$MIN_VIEW_COLOURS \
                -v mr=$MIN_VIEW_ROTATED '
    BEGIN {
      if (c == "") { print "its self-check did not run (script not run or over the time budget)"; exit; }
      if (c == "nowebgl") { print "no WebGL in this Chromium (SwiftShader flags?)"; exit; }
      if (c ~ /^error/) { print "script failed: " c; exit; }
      n = split(c, kv, " ");
      for (i = 1; i <= n; ++i) { split(kv[i], p, "="); v[p[1]] = p[2]; }
      if (!("rotated" in v)) { print "unreadable check (" c ")"; exit; }
      if (v["w"] < mw || v["h"] < mh) { print "too small: " v["w"] "x" v["h"] " px"; exit; }
      if (v["faces"] < 1) { print "no faces drawn"; exit; }
      if (v["ink"] < mi || v["colours"] < mc) { print "blank: ink " v["ink"] ", " v["colours"] " colours"; exit; }
      if (v["rotated"] < mr) { print "does not turn: rotating the camera changed " v["rotated"] " of the pixels"; exit; }
      print "ok";
    }')
  if [ "$verdict" = ok ]; then
    echo "ok   3D view ($check)"
  else
    echo "FAIL 3D view: $verdict"
    failed=1
  fi
fi

# Screenshot of the whole page, then its ink and colours measured by Chromium itself.
height=$(grep -o 'data-page-height="[0-9]*"' "$tmp/dom.html" | grep -o '[0-9]*' || echo 4000)
height=$(( height < 16000 ? height : 16000 ))
"$chromium" "${flags[@]}" --hide-scrollbars --window-size=$WINDOW_WIDTH,$height \
  --force-device-scale-factor="${SCREENSHOT_SCALE:-1}" \
  --screenshot="$shot" "file://$report" 2>"$tmp/chromium.log" >/dev/null || {
  echo "FAIL $1: chromium could not take a screenshot"; tail -5 "$tmp/chromium.log"; exit 1; }
[ -s "$shot" ] || { echo "FAIL $1: no screenshot written"; exit 1; }
{
  echo '<!DOCTYPE html><html><body><img id="s" src="data:image/png;base64,'
  base64 -w0 "$shot"
  cat <<'EOF'
"><script>
window.addEventListener('load', function () {
  const img = document.getElementById('s');
  const c = document.createElement('canvas');
  c.width = img.naturalWidth; c.height = img.naturalHeight;
  const g = c.getContext('2d');
  g.drawImage(img, 0, 0);
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let ink = 0; const colours = new Set();
  for (let i = 0; i < d.length; i += 4) {
    if (d[i] < 245 || d[i + 1] < 245 || d[i + 2] < 245) ++ink;
    colours.add(((d[i] >> 4) << 8) | ((d[i + 1] >> 4) << 4) | (d[i + 2] >> 4));
  }
  document.body.dataset.shot = 'size=' + c.width + 'x' + c.height + ' ink=' +
      (ink / (d.length / 4)).toFixed(3) + ' colours=' + colours.size;
});
</script></body></html>
EOF
} > "$tmp/shot.html"
shot_check=$(dump_dom "file://$tmp/shot.html" | grep -o 'data-shot="[^"]*"' | sed -E 's/data-shot="(.*)"/\1/' || true)
verdict=$(awk -v c="$shot_check" -v mi=$MIN_PAGE_INK -v mc=$MIN_PAGE_COLOURS '
  BEGIN {
    n = split(c, kv, " ");
    for (i = 1; i <= n; ++i) { split(kv[i], p, "="); v[p[1]] = p[2]; }
    if (!("ink" in v)) { print "unreadable"; exit; }
    if (v["ink"] < mi || v["colours"] < mc) { print "blank"; exit; }
    print "ok";
  }')
if [ "$verdict" = ok ]; then
  echo "ok   screenshot $shot ($shot_check)"
else
  echo "FAIL screenshot $shot: $verdict ($shot_check)"
  failed=1
fi
exit $failed
