#!/usr/bin/env bash
# index.html in a real browser: writes the report of a budget (no plots:
# the page needs none), opens its index.html in headless Chromium through
# chromedriver's WebDriver HTTP API and checks that
#   - the page loads without a console error or warning from its scripts,
#   - every figure is drawn: each figure.chart holds a canvas with at least
#     500 pixels that are neither blank nor white,
#   - hovering each figure shows a value with its frequency in its legend,
#   - a legend box hides its contributor, the ASD box relabels the PSD,
#   - a drag on an output's CPS zooms its PSD too (their x-axis labels change),
#   - the verdict has a line per requirement, green where met and red where not,
#   - every CPS stacks the groups and reads as RMS on a right axis.
# Exit 77 (CTest: skipped) when chromium or chromedriver is missing.
# Usage: index_html_browser_test.sh DEB_BINARY BUDGET.yaml
# With DEB_SCREENSHOTS=DIR, the top of the page and each figure while hovered
# are saved there as PNG.
set -euo pipefail

deb=$1
budget=$2
for tool in chromium chromedriver curl jq; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool is not installed (tools/install-deps installs it)"
    exit 77
  fi
done

work=$(mktemp -d)
driver_pid=
session=
cleanup() {
  [ -n "$session" ] && curl -s -X DELETE "$base/session/$session" >/dev/null || true
  [ -n "$driver_pid" ] && kill "$driver_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

"$deb" run "$budget" --out "$work/report" --no-plots --quiet
page="file://$work/report/index.html"

# chromedriver on a free port (tests may run in parallel).
for attempt in 1 2 3 4 5; do
  port=$((20000 + RANDOM % 20000))
  chromedriver --port="$port" >"$work/chromedriver.log" 2>&1 &
  driver_pid=$!
  base="http://127.0.0.1:$port"
  for _ in $(seq 50); do
    curl -s "$base/status" 2>/dev/null | jq -e '.value.ready' >/dev/null 2>&1 && break
    sleep 0.1
  done
  curl -s "$base/status" 2>/dev/null | jq -e '.value.ready' >/dev/null 2>&1 && break
  kill "$driver_pid" 2>/dev/null || true
  driver_pid=
done
[ -n "$driver_pid" ] || { echo "FAIL: chromedriver did not start"; cat "$work/chromedriver.log"; exit 1; }

fail=0
check() {  # check CONDITION_TEXT OK(0/1)
  if [ "$2" = 1 ]; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi
}
post() { curl -s -X POST -H 'Content-Type: application/json' -d "$2" "$base/session/$session$1"; }
# Runs JavaScript in the page; prints its return value as JSON.
js() { post /execute/sync "$(jq -n --arg s "$1" '{script: $s, args: []}')" | jq -c '.value'; }

shot() { curl -s "$base/session/$session/screenshot" | jq -r '.value' | base64 -d >"$1"; }

caps=$(jq -n --arg bin "$(command -v chromium)" '{capabilities: {alwaysMatch: {
  browserName: "chrome", "goog:loggingPrefs": {browser: "ALL"},
  "goog:chromeOptions": {binary: $bin, args: ["--headless=new", "--no-sandbox", "--disable-gpu",
                                             "--disable-dev-shm-usage", "--window-size=1280,1000"]}}}}')
session=$(curl -s -X POST -H 'Content-Type: application/json' -d "$caps" "$base/session" | jq -r '.value.sessionId')
[ -n "$session" ] && [ "$session" != null ] || { echo "FAIL: no browser session"; cat "$work/chromedriver.log"; exit 1; }

post /url "$(jq -n --arg u "$page" '{url: $u}')" >/dev/null
drawn=0
for _ in $(seq 100); do
  [ "$(js "return document.documentElement.getAttribute('data-figures');")" = '"drawn"' ] && { drawn=1; break; }
  sleep 0.1
done
check "the page's script ran to its end" "$drawn"
echo "info: page drawn after $(js "return Math.round(performance.now());") ms, $(stat -c %s "$work/report/index.html") bytes"
[ -n "${DEB_SCREENSHOTS:-}" ] && mkdir -p "$DEB_SCREENSHOTS" && shot "$DEB_SCREENSHOTS/top.png"

figures=$(js "return document.querySelectorAll('figure.chart').length;")
check "the page has figures ($figures)" "$([ "$figures" -gt 0 ] && echo 1 || echo 0)"

# Figures whose canvases hold fewer than 500 drawn pixels.
blank=$(js "
  var out = [];
  document.querySelectorAll('figure.chart').forEach(function (fig, i) {
    var drawn = 0;
    fig.querySelectorAll('canvas').forEach(function (c) {
      if (!c.width || !c.height) return;
      var px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      for (var k = 0; k < px.length; k += 4)
        if (px[k + 3] > 0 && (px[k] < 235 || px[k + 1] < 235 || px[k + 2] < 235)) drawn++;
    });
    if (drawn < 500) out.push(fig.getAttribute('data-kind') + ' ' + fig.getAttribute('data-index') + ': ' + drawn);
  });
  return out;")
check "every figure has a drawn canvas (blank: $blank)" "$([ "$blank" = '[]' ] && echo 1 || echo 0)"

# The verdict: a line per requirement, each coloured by its own verdict
# (a passing line of a failing budget is green, not red).
verdict=$(js "
  var bg = function (p) { return getComputedStyle(p).backgroundColor; };
  var pass = document.querySelectorAll('#verdict p.pass'), fail = document.querySelectorAll('#verdict p.fail');
  var greens = Array.prototype.filter.call(pass, function (p) { return bg(p) === 'rgb(27, 120, 55)'; }).length;
  var reds = Array.prototype.filter.call(fail, function (p) { return bg(p) !== 'rgb(27, 120, 55)'; }).length;
  return [pass.length, greens, fail.length, reds].join(' ');")
read -r n_pass n_green n_fail n_red <<<"${verdict//\"/}"
check "the verdict has a line per requirement, green where met ($n_green of $n_pass), red where not ($n_red of $n_fail)" \
  "$([ "$n_pass" -ge 1 ] && [ "$n_green" = "$n_pass" ] && [ "$n_fail" -ge 1 ] && [ "$n_red" = "$n_fail" ] && echo 1 || echo 0)"

# Each CPS stacks what its PNG stacks (the budget's top-level groups, "name/")
# and reads on the right as RMS: labels of the rms-axis at round values.
cps=$(js "
  var out = [];
  document.querySelectorAll('figure.chart[data-kind=cps]').forEach(function (fig) {
    var toggles = Array.prototype.map.call(fig.querySelectorAll('.toggles label'), function (l) { return l.textContent; });
    var groups = toggles.filter(function (t) { return /\/$/.test(t); }).length;
    out.push(groups + ':' + fig.querySelectorAll('.rms-axis').length);
  });
  return out.join(' ');")
bad_cps=0
cps=${cps//\"/}
for c in $cps; do
  groups=${c%%:*}; labels=${c##*:}
  { [ "$groups" -ge 1 ] && [ "$labels" -ge 3 ]; } || bad_cps=1
done
check "every CPS stacks the groups and has an RMS axis (groups:labels per CPS: $cps)" "$([ "$bad_cps" = 0 ] && echo 1 || echo 0)"

# Hover: the pointer at 40 % of each figure's plot area; its legend must then
# give a frequency and a number.
element_key=element-6066-11e4-a52e-4f735466cecf
no_value=()
for ((i = 0; i < figures; i++)); do
  js "var p = document.querySelectorAll('figure.chart .plot')[$i]; p.scrollIntoView({block: 'center'}); return 0;" \
    >/dev/null
  el=$(post /elements '{"using": "css selector", "value": "figure.chart .plot"}' | jq -r ".value[$i][\"$element_key\"]")
  width=$(js "return Math.round(document.querySelectorAll('figure.chart .plot')[$i].getBoundingClientRect().width);")
  dx=$((width * 40 / 100 - width / 2))
  post /actions "$(jq -n --arg el "$el" --argjson dx "$dx" --arg key "$element_key" '{actions: [{type: "pointer",
      id: "mouse", parameters: {pointerType: "mouse"}, actions: [
      {type: "pointerMove", duration: 0, origin: {($key): $el}, x: ($dx - 5), y: 0},
      {type: "pointerMove", duration: 50, origin: {($key): $el}, x: $dx, y: 0}]}]}')" >/dev/null
  legend=$(js "return document.querySelectorAll('figure.chart')[$i].querySelector('.legend').textContent;")
  if ! [[ "$legend" =~ Hz ]] || ! [[ "$legend" =~ :\ -?[0-9] ]]; then
    no_value+=("$i: $legend")
  fi
  [ -n "${DEB_SCREENSHOTS:-}" ] && shot "$DEB_SCREENSHOTS/figure_$i.png"
done
check "hovering every figure shows values in its legend (without: ${no_value[*]:-none})" \
  "$([ ${#no_value[@]} -eq 0 ] && echo 1 || echo 0)"
post /actions '{"actions": [{"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
  "actions": [{"type": "pointerMove", "duration": 0, "x": 1, "y": 1}]}]}' >/dev/null

# A legend box hides its contributor: unticking the first of the first CPS
# takes that contributor out of the hover legend; the ASD box relabels the PSD.
name=$(js "return document.querySelector('figure.chart[data-kind=cps] .toggles label').textContent;")
box=$(post /element '{"using": "css selector", "value": "figure.chart[data-kind=cps] .toggles input"}' |
  jq -r ".value[\"$element_key\"]")
post "/element/$box/click" '{}' >/dev/null
el=$(post /element '{"using": "css selector", "value": "figure.chart[data-kind=cps] .plot"}' | jq -r ".value[\"$element_key\"]")
post /actions "$(jq -n --arg el "$el" --arg key "$element_key" '{actions: [{type: "pointer", id: "mouse",
    parameters: {pointerType: "mouse"}, actions: [{type: "pointerMove", duration: 0, origin: {($key): $el}, x: 20, y: 0},
    {type: "pointerMove", duration: 50, origin: {($key): $el}, x: 25, y: 0}]}]}')" >/dev/null
legend=$(js "return document.querySelector('figure.chart[data-kind=cps] .legend').textContent;")
check "unticking $name hides it from the legend ($legend)" \
  "$([[ "$legend" =~ total ]] && ! [[ "$legend" == *"${name//\"/}: "* ]] && echo 1 || echo 0)"
post "/element/$box/click" '{}' >/dev/null
box=$(post /element '{"using": "css selector", "value": "figure.chart[data-kind=psd] .toggles input.asd"}' |
  jq -r ".value[\"$element_key\"]")
post "/element/$box/click" '{}' >/dev/null
ylabel=$(js "return document.querySelector('figure.chart[data-kind=psd] .dygraph-ylabel').textContent;")
check "the ASD box shows amplitudes ($ylabel)" "$([[ "$ylabel" == *ASD*√Hz* ]] && echo 1 || echo 0)"
post "/element/$box/click" '{}' >/dev/null

# Linked zoom: drag across the middle of the first output's CPS.
ticks='function ticks(kind) {
  var f = document.querySelector("figure.chart[data-kind=" + kind + "][data-index=\"0\"]");
  return Array.prototype.map.call(f.querySelectorAll(".dygraph-axis-label-x"), function (e) { return e.textContent; }).join(" ");
}'
js "document.querySelector('figure.chart[data-kind=cps] .plot').scrollIntoView({block: 'center'}); return 0;" >/dev/null
before=$(js "$ticks; return [ticks('cps'), ticks('psd')];")
el=$(post /element '{"using": "css selector", "value": "figure.chart[data-kind=cps] .plot"}' | jq -r ".value[\"$element_key\"]")
post /actions "$(jq -n --arg el "$el" --arg key "$element_key" '{actions: [{type: "pointer", id: "mouse",
    parameters: {pointerType: "mouse"}, actions: [
    {type: "pointerMove", duration: 0, origin: {($key): $el}, x: -60, y: 0}, {type: "pointerDown", button: 0},
    {type: "pointerMove", duration: 200, origin: {($key): $el}, x: 80, y: 0}, {type: "pointerUp", button: 0}]}]}')" \
  >/dev/null
after=$(js "$ticks; return [ticks('cps'), ticks('psd')];")
check "a drag on the CPS zooms it and its PSD: $before -> $after" \
  "$(jq -n --argjson b "$before" --argjson a "$after" 'if $b[0] != $a[0] and $b[1] != $a[1] then 1 else 0 end')"

# Console messages of the page (errors and warnings; the log holds what the
# page printed since it was opened).
log=$(post /se/log '{"type": "browser"}')
problems=$(jq -c '[.value[] | select(.level == "SEVERE" or .level == "WARNING") | .message]' <<<"$log")
check "no console errors or warnings ($problems)" "$([ "$problems" = '[]' ] && echo 1 || echo 0)"

exit $fail
