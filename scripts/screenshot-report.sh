#!/usr/bin/env bash
# Render the validation report (report.html) in headless Chromium and save screenshots:
# the top of the page, every drawing in one grid (`report.html?drawings`) stopped at the
# start, the middle and the end of each run (`&at=0`, `0.5`, `1`) and once running, and each
# chosen case alone (`report.html?case=NN`), its drawing stopped half-way.
#
#   scripts/screenshot-report.sh [OUT_DIR] [CASE ...]      (default: target/report-shots, 15 19 21 28)
#
# Needs Chromium (Debian: `apt-get install chromium`). Writes the report itself with
# `cargo run --release -p mechanisms --bin validate -- --out OUT_DIR/report`.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/report-shots}"
shift || true
cases=("$@")
[ ${#cases[@]} -gt 0 ] || cases=(15 19 21 28)
browser="$(command -v chromium || command -v chromium-browser || command -v chromium-headless-shell || true)"
if [ -z "$browser" ]; then
    echo "error: no Chromium found (Debian: apt-get install chromium)" >&2
    exit 2
fi
mkdir -p "$out"
cargo run --release -q -p mechanisms --bin validate -- --out "$out/report" > /dev/null
page="file://$(realpath "$out/report/report.html")"
shot() { # name, width, height, url
    "$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars \
        --window-size="$2,$3" --virtual-time-budget=2500 \
        --screenshot="$out/$1.png" "$4" > /dev/null 2>&1
    echo "$out/$1.png"
}
shot top 1100 1400 "$page"
for at in 0 0.5 1; do
    shot "drawings-at-$at" 1400 2700 "$page?drawings&at=$at"
done
shot drawings 1400 2700 "$page?drawings"
for c in "${cases[@]}"; do
    shot "case$c" 1100 1100 "$page?case=$c&at=0.5"
done
