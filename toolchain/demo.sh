#!/usr/bin/env bash
# The main job from a fresh machine: installs the dependencies, builds the release preset and
# runs a short walk optimisation in the simulator (optimiser/configs/walk-demo.json: the seed's
# walk task, 40 s time limit and 2.5 m goal, with pop 12 and 5 generations; about a minute on
# 2 cores), validates Ind_O and the picks on unseen worlds (validation.json; 3 seeds per world),
# prints the report with the validation in words, and ends with what to open (report.html) and
# what to try next (flash a pick with the parameter console, run the full task).
set -euo pipefail
cd "$(dirname "$0")/.."

toolchain/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target stride stride-fw

bin="build/release/bin"
out="demo-run"
rm -rf "$out"
echo "== stride optimise: walk demo (pop 12, 5 generations, 40 s limit) into $out/"
"$bin/stride" optimise --config optimiser/configs/walk-demo.json --out "$out"
echo "== stride report $out"
"$bin/stride" report "$out" | tee "$out/report.txt"

# The pick to flash: the one that holds in most validation worlds, else the knee point.
pick=$(sed -n 's/^  the pick that holds in most worlds: .*, \(front\/[^ ]*\.json\)$/\1/p' \
  "$out/report.txt")
[ -n "$pick" ] || pick=$(awk '$1 == "knee" { print $NF }' "$out/report.txt")
[ -n "$pick" ] || pick="front/000.json"
cat <<NEXT

== what next
1. Open $out/report.html in a browser (one file, works offline): Ind_O and the picks replayed
   in 3D, the fronts, the accelerometer, the validation table.
2. Flash a pick with the parameter console: $out/$pick (the pick that holds in most worlds).
   Without a robot, on the simulated robot behind the Dynamixel protocol:
     $bin/stride vbus --link /tmp/stride-robot --sim &
     $bin/stride-fw --hal serial --port /tmp/stride-robot --console stdio
   then type: load $out/$pick, walk 1 0 0, status, stop; Ctrl-C ends stride-fw, kill %1 the bus.
   (The run scored walking to the goal, not stopping: a pick may fall on stop where Ind_O does
   not; the firmware then starts its get-up.)
   On the robot, with stride-fw --hal serial --port /dev/ttyUSB0 --console /dev/ttyS1 running:
     $bin/stride console --port /dev/ttyS1 flash $out/$pick --verify
3. Run the full task, the seed's walk run (pop 40, 50 generations, 10 seeds per world in the
   validation; about 5 minutes on 2 cores):
     $bin/stride optimise --config optimiser/configs/walk.json --out runs/walk --jobs 2
     $bin/stride report runs/walk
NEXT
