#!/usr/bin/env bash
# The documentation's images, made again from a built tree (scripts/build.sh first):
#
#   scripts/doc-images.sh
#
# Runs the main demo (pss-paper-figures, whose figures examples/pvpython/render_paper_figures.py
# renders in pvbatch under xvfb-run), then the ParaView examples figure9_10_scene.py,
# bunny_mesh.py and real_frame_mesh.py (two frames of ../shared/data/real-scans, when present) with
# the plugin, all into BUILD/doc-images, and copies into docs/images exactly the
# images that README.md and docs/*.md show; an image there that no page shows is removed. Fails
# when a page shows an image that none of these programs made. Commit docs/images afterwards.
# Environment: PSS_BUILD_DIR (default build/), PSS_DOC_IMAGES_DIR (where the programs write,
# default BUILD/doc-images).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PSS_BUILD_DIR:-$root/build}"
demo="$build/bin/pss-paper-figures"
plugin="$build/lib/paraview-plugins/PointSetSurfaces"
out="${PSS_DOC_IMAGES_DIR:-$build/doc-images}"
images="$root/docs/images"

if [ ! -x "$demo" ] || [ ! -d "$plugin" ]; then
  echo "doc-images.sh: $demo or $plugin is missing: build first (scripts/build.sh)" >&2
  exit 1
fi
for tool in pvbatch xvfb-run; do
  if ! command -v "$tool" > /dev/null; then
    echo "doc-images.sh: $tool is not on PATH (scripts/install-deps.sh installs it)" >&2
    exit 1
  fi
done
mkdir -p "$out"

# pvbatch under a virtual X server. `xvfb-run -a` now and then fails to reach the server it just
# started ("bad X server connection") when runs follow each other closely: up to three tries.
render() {
  local attempt
  for attempt in 1 2 3; do
    if xvfb-run -a pvbatch "$@"; then
      return 0
    fi
    echo "doc-images.sh: pvbatch under xvfb-run failed (try $attempt of 3)" >&2
    sleep 2
  done
  return 1
}

echo "doc-images.sh: the main demo and its figures"
"$demo" --out "$out/paper-figures" --renderer "$root/examples/pvpython/render_paper_figures.py"
echo "doc-images.sh: the Figure 9 scene in ParaView"
render "$root/examples/pvpython/figure9_10_scene.py" --plugin "$plugin" --size 960x640 \
  --output "$out/figure9_10_scene.png"
echo "doc-images.sh: the bunny mesh in ParaView"
render "$root/examples/pvpython/bunny_mesh.py" --plugin "$plugin" --size 960x480 \
  --output "$out/bunny_mesh.png"
scans="${PSS_SHARED_DATA_DIR:-$root/../shared/data}/real-scans"
real_frames=(test9 region_growing_rgb_tutorial)
if [ -f "$scans/test9.pcd" ]; then
  echo "doc-images.sh: real depth-camera frames meshed in ParaView"
  for frame in "${real_frames[@]}"; do
    render "$root/examples/pvpython/real_frame_mesh.py" --plugin "$plugin" --size 1600x640 \
      --frame "$scans/$frame.pcd" --output "$out/real_frame_${frame%_rgb_tutorial}.png"
  done
else
  echo "doc-images.sh: no $scans: the real frames' images keep their committed copies"
fi

# The images the pages show: every ](...images/NAME.png) of README.md and docs/*.md.
mapfile -t shown < <(grep -ohE '\]\((docs/)?images/[A-Za-z0-9_.-]+\.png' "$root/README.md" "$root"/docs/*.md \
  | sed -E 's|.*images/||' | sort -u)
mkdir -p "$images"
for name in "${shown[@]}"; do
  made=""
  for candidate in "$out/$name" "$out/paper-figures/$name"; do
    if [ -f "$candidate" ]; then
      made="$candidate"
    fi
  done
  if [ -z "$made" ] && [[ "$name" == real_frame_* ]] && [ ! -f "$scans/test9.pcd" ]; then
    continue # made from the shared data, which is not here
  fi
  if [ -z "$made" ]; then
    echo "doc-images.sh: a page shows images/$name, which no program here made" >&2
    exit 1
  fi
  cp "$made" "$images/$name"
  echo "doc-images.sh: docs/images/$name"
done
for existing in "$images"/*; do
  name="$(basename "$existing")"
  if ! printf '%s\n' "${shown[@]}" | grep -qxF "$name"; then
    echo "doc-images.sh: removing docs/images/$name (no page shows it)"
    rm -f "$existing"
  fi
done
echo "doc-images.sh: done; commit docs/images"
