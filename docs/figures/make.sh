#!/bin/sh
# Regenerates the README's gallery: the paper's Fig. 2-5 drawn by `bouncemap figure` at
# the paper's fidelity (Fig. 3 and 4: 1000 values per diagram, T = 5·10⁶, last 100
# events). Builds the release binary first. On an idle 2-core machine Fig. 3 takes about
# a minute and Fig. 4 about five (values that never settle run the whole transient);
# the (α, D) plane after them, about 15 s with its curves, the curves figure about 20 s,
# the attractors along α about 5 s, the manifolds over the basins about 1 s and the
# crises of the sine's two-band attractor (its jump in size and its destruction) about
# 90 s.
set -eu
cd "$(dirname "$0")/../.."
cargo build --release --locked
bouncemap() { target/release/bouncemap "$@"; }

bouncemap figure fig2 --dpi 200 --out docs/figures/fig2.png
bouncemap figure fig3 --dpi 200 --out docs/figures/fig3.png
bouncemap figure fig4 --dpi 200 --out docs/figures/fig4.png
bouncemap figure fig5 --dpi 200 --out docs/figures/fig5.png
bouncemap figure plane --x alpha:0.45..0.60 --y d:0..1 --r 0.8 --pixels 400x200 --curves 8 --dpi 200 --out docs/figures/plane.png
bouncemap figure curves --table fd --x alpha:0.45..0.7 --y d:0..1 --max-period 16 --dpi 200 --out docs/figures/curves.png
bouncemap figure attractors --table cubic --r 0.8 --alpha 0.44..0.56 --steps 121 --grid 60x60 --dpi 200 --out docs/figures/attractors.png
bouncemap figure basins --table cubic --alpha 0.47 --grid 400x200 --manifolds --dpi 200 --out docs/figures/basins-manifolds.png
bouncemap figure attractors --table sine --r 0.8 --alpha 0.0316..0.0319 --steps 31 --grid 24x24 --crises --dpi 200 --out docs/figures/crisis.png
