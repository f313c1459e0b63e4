#!/usr/bin/env bash
# Fetches the iCub Grasp Dataset (Soh, Su and Demiris, 2012; 230 recordings of a real iCub hand's
# five fingertips) into a folder, default data/icub_grasp_2012, for the full analysis of
# docs/real-fingertips.md. Needs git and a network; nothing else in the workbench downloads.
set -euo pipefail
dest="${1:-data/icub_grasp_2012}"
if [ -d "$dest/iCubGraspDataset" ]; then
  echo "fetch-icub-grasp-dataset: $dest already holds the dataset"
  exit 0
fi
git clone --depth 1 https://github.com/clear-nus/icub_grasp_dataset "$dest"
echo "fetched $(ls "$dest"/iCubGraspDataset/*.txt | wc -l) recordings into $dest/iCubGraspDataset"
echo "next: activetouch-cli import-frames experiments/layouts/icub_grasp_2012.json" \
  "$dest/iCubGraspDataset/*.txt --out results/icub_grasp_frames"
