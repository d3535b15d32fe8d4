#!/usr/bin/env bash
# Checks the OpenJD template and runs it on this machine with openjd-cli (pinned, in a venv of
# its own), then compares each merged image with the whole render byte for byte.
# Usage: bash farm/openjd/check.sh [RAYTRACER_BINARY]   (default: target/release/raytracer)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin="$(realpath "${1:-target/release/raytracer}")"
venv="target/openjd-venv"
if [ ! -x "$venv/bin/openjd" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet --disable-pip-version-check openjd-cli==0.8.0
fi
template=farm/openjd/tiled-render.yaml
"$venv/bin/openjd" check "$template"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# The scenes keep their place beside the textures they name (../textures/...).
mkdir -p "$work/scenes" "$work/textures"
cp scenes/penumbra.json scenes/thinlens.json "$work/scenes/"
cp textures/checker.png "$work/textures/"
# scene, output, columns, rows, spp (0: the scene's own)
while read -r scene out cols rows spp; do
    "$venv/bin/openjd" run "$template" --step Merge --run-dependencies \
        -p SceneFile="$work/scenes/$scene" -p OutputFile="$work/merged-$out" \
        -p TilesX="$cols" -p TilesY="$rows" -p Spp="$spp" -p Raytracer="$bin" \
        >"$work/log" 2>&1 || { cat "$work/log"; exit 1; }
    whole=(--quiet --threads 1)
    if [ "$spp" -gt 0 ]; then whole+=(--spp "$spp"); fi
    "$bin" "$work/scenes/$scene" "$work/whole-$out" "${whole[@]}"
    if ! cmp "$work/whole-$out" "$work/merged-$out"; then
        echo "openjd: $scene in $cols×$rows tiles differs from the whole render" >&2
        exit 1
    fi
    echo "openjd: $scene in $cols×$rows tiles, $out: identical to the whole render"
done <<'JOBS'
penumbra.json penumbra.png 3 2 4
thinlens.json thinlens.exr 5 1 2
JOBS
