#!/usr/bin/env bash
# The main job on the embedded defaults: installs what is missing, builds auvloop, then describes
# the REMUS 100 preset and exports its surface (straight and with 20 deg rudder) into out/quickstart/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh build/release -DCMAKE_BUILD_TYPE=Release -DAUVLOOP_BUILD_TESTS=OFF
auvloop=build/release/client/auvloop
out=out/quickstart
mkdir -p "$out"
"$auvloop" geometry info
"$auvloop" geometry info --json > "$out/remus100-geometry.json"
"$auvloop" geometry export --out "$out/remus100.stl"
"$auvloop" geometry export --rudder 20 --out "$out/remus100-rudder20.glb"
echo "quickstart: results in $out/ (open the .stl or .glb in ParaView or any mesh viewer)"
