#!/usr/bin/env bash
# A raytracer render split over a Slurm cluster: one array task per tile, then a merge job that
# starts only when every tile has succeeded. Run it on the login node, from a folder every node
# sees (the tiles are written there):
#
#   bash farm/slurm/tiled-render.sh SCENE.json OUT.png COLS ROWS [extra raytracer flags...]
#
# e.g. `bash farm/slurm/tiled-render.sh scenes/demo.json demo.png 8 8 --spp 256`. The extra flags
# (--spp, --seed, ...) go to every tile; the merge takes the tone map from --tonemap if given.
set -euo pipefail
scene=$1 out=$2 cols=$3 rows=$4
shift 4
tiles="tiles-$(basename "$scene" .json)"
mkdir -p "$tiles"
n=$((cols * rows))
# Array task k renders cell (k mod COLS, k div COLS) of the grid.
render=$(sbatch --parsable --array=0-$((n - 1)) --cpus-per-task=1 \
    --job-name=raytracer-tiles --output="$tiles/%a.log" \
    --wrap="raytracer '$scene' '$tiles/tile-\$SLURM_ARRAY_TASK_ID.exr' \
            --tile \$((SLURM_ARRAY_TASK_ID % $cols)),\$((SLURM_ARRAY_TASK_ID / $cols)) \
            --tiles $cols,$rows --threads \$SLURM_CPUS_PER_TASK --quiet $*")
sbatch --dependency=afterok:"$render" --job-name=raytracer-merge --output="$tiles/merge.log" \
    --wrap="raytracer merge '$out' '$tiles'/tile-*.exr"
echo "submitted: tiles as array job $render, merge after it; logs in $tiles/"
