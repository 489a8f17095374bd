#!/usr/bin/env bash
# Stride's report pages in a real browser: makes a tiny walk run and a tiny kick run (seconds)
# and a tinier walk run on the hard ground with a renamed URDF, `stride report` on each (the
# walk run with the validation.json its optimise wrote) and on a run directory with nothing
# evaluated yet, and a
# `stride sim kick --html` page, then loads every page in headless Chromium (check_page.cjs:
# no console error, no network, every section present and not empty, the replay drawn and its
# time advancing after Play, the 3D view showing the robot and moved by the slider, the run's
# own ground and robot drawn) and writes
# screenshots to OUT_DIR. The 3D view's bad inputs: a page made without three.js, and copies of
# the sim-kick page with its trajectory cut short or emptied, each saying so.
#
# usage: run_browser_tests.sh STRIDE_BINARY OUT_DIR SOURCE_DIR
# Chromium: $STRIDE_CHROMIUM or chromium on the PATH; puppeteer-core:
# $STRIDE_BROWSER_MODULES, else /opt/stride/browser-test/node_modules (toolchain/install-deps.sh),
# else installed into OUT_DIR/node with npm ci. Exit 77 (ctest: skipped) only when no browser or
# no node is installed, saying so.
set -euo pipefail
stride=$1 out=$2 src=$3
here="$src/tests/browser"

chromium=${STRIDE_CHROMIUM:-}
if [[ -z "$chromium" ]]; then
  for c in chromium chromium-browser google-chrome; do
    if command -v "$c" >/dev/null; then chromium=$(command -v "$c"); break; fi
  done
fi
if [[ -z "$chromium" ]]; then
  echo "SKIPPED: no Chromium on this machine (toolchain/install-deps.sh installs Debian's chromium)"
  exit 77
fi
if ! command -v node >/dev/null; then
  echo "SKIPPED: no node on this machine to drive Chromium (toolchain/install-deps.sh installs it)"
  exit 77
fi
modules=${STRIDE_BROWSER_MODULES:-/opt/stride/browser-test/node_modules}
if [[ ! -f "$modules/puppeteer-core/package.json" ]]; then
  echo "puppeteer-core not in $modules: installing it into $out/node (npm ci)"
  mkdir -p "$out/node"
  cp "$here/package.json" "$here/package-lock.json" "$out/node/"
  (cd "$out/node" && PUPPETEER_SKIP_DOWNLOAD=1 npm ci --no-audit --no-fund --ignore-scripts >/dev/null)
  modules="$out/node/node_modules"
fi

runs="$out/runs"
rm -rf "$runs" "$out"/*.png
mkdir -p "$runs"
echo "== tiny runs (pop 4, 2 generations)"
"$stride" optimise --config "$src/optimiser/configs/walk-demo.json" --out "$runs/walk" --pop 4 \
  --generations 2 --jobs 2 >/dev/null 2>"$runs/walk.log"
"$stride" optimise --config "$src/optimiser/configs/kick.json" --out "$runs/kick" --pop 4 \
  --generations 2 --jobs 2 --no-validate >/dev/null 2>"$runs/kick.log"
# The walk run was validated at its end (walk-demo.json: validate.seeds 3): its page has the
# validation section; the kick run (--no-validate) has none.
test -s "$runs/walk/validation.json"
test ! -e "$runs/kick/validation.json"
# A run in another world: the hard ground and the igus URDF under another robot name (its page
# must draw that ground, 3 mm, and that robot, not the seed's 2 cm grass and the igus model).
sed 's/<robot name="igus_op">/<robot name="igus_op_renamed">/' \
  "$src/sim_hal/models/igus_op.urdf" >"$runs/igus_op_renamed.urdf"
grep -q 'name="igus_op_renamed"' "$runs/igus_op_renamed.urdf"
node -e '
const fs = require("fs");
const [from, to, urdf] = process.argv.slice(1);
const c = JSON.parse(fs.readFileSync(from, "utf8"));
c.world = {contact: "hard", urdf: urdf};
fs.writeFileSync(to, JSON.stringify(c));
' "$src/optimiser/configs/walk-demo.json" "$runs/walk-hard.json" "$runs/igus_op_renamed.urdf"
"$stride" optimise --config "$runs/walk-hard.json" --out "$runs/walk-hard" --pop 4 \
  --generations 1 --jobs 2 --no-validate >/dev/null 2>"$runs/walk-hard.log"
# A run that has evaluated nothing yet.
mkdir -p "$runs/empty"
cp "$runs/walk/run.json" "$runs/empty/"
: >"$runs/empty/evaluations.jsonl"

echo "== stride report / stride sim --html"
"$stride" report "$runs/walk"
"$stride" report "$runs/kick"
"$stride" report "$runs/walk-hard"
"$stride" report "$runs/empty" 2>&1
"$stride" sim kick --duration 6 --html "$runs/sim-kick.html"
# The 3D view's bad inputs: no three.js at report time (one warning line, the page says so),
# and pages whose trajectory data is broken (cut short) or missing (emptied).
STRIDE_THREE_JS=/nonexistent/three.min.js "$stride" sim stand --duration 1 \
  --html "$runs/sim-no-three.html" 2>"$runs/sim-no-three.err"
test "$(wc -l <"$runs/sim-no-three.err")" -eq 1
grep -q 'warning: the 3D replay is unavailable: three.js not found' "$runs/sim-no-three.err"
node -e '
const fs = require("fs");
const [page, broken, missing] = process.argv.slice(1);
const html = fs.readFileSync(page, "utf8");
const motion = /"motion":"([A-Za-z0-9+\/=]+)"/;
if (!motion.test(html)) throw new Error(page + ": no 3D motion data");
fs.writeFileSync(broken, html.replace(motion, (m, d) => "\"motion\":\"" + d.slice(0, d.length / 2 - (d.length / 2) % 4) + "\""));
fs.writeFileSync(missing, html.replace(motion, "\"motion\":\"\""));
' "$runs/sim-kick.html" "$runs/sim-kick-broken.html" "$runs/sim-kick-missing.html"

echo "== pages in $chromium"
report_sections=settings,picks,pareto,hypervolume,accelerometer,poses,replay,parameters
status=0
node "$here/check_page.cjs" --chromium "$chromium" --modules "$modules" --out "$out" \
  --name walk --page "$runs/walk/report.html" --sections "$report_sections,validation" \
  --replay 2 --replay3d --world turf,0.005,igus_op \
  --name kick --page "$runs/kick/report.html" --sections "$report_sections" --replay 2 \
  --replay3d \
  --name walk-hard --page "$runs/walk-hard/report.html" --sections "$report_sections" \
  --replay 1 --replay3d --world hard,0.003,igus_op_renamed \
  --name empty --page "$runs/empty/report.html" --sections "$report_sections" --replay 1 \
  --expect-warnings \
  --name sim-kick --page "$runs/sim-kick.html" --sections episode,accelerometer,poses,replay \
  --replay 1 --replay3d \
  --name sim-no-three --page "$runs/sim-no-three.html" --sections episode,replay --replay 1 \
  --expect-warnings --replay3d-unavailable 'unavailable: three\.js not found' \
  --name sim-kick-broken --page "$runs/sim-kick-broken.html" --sections episode,replay \
  --replay 1 --replay3d-unavailable 'unavailable: .*trajectory is broken' \
  --name sim-kick-missing --page "$runs/sim-kick-missing.html" --sections episode,replay \
  --replay 1 --replay3d-unavailable 'unavailable: .*no trajectory was recorded' || status=1
ls "$out"/*.png
exit $status
