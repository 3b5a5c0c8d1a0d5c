// The roof corpus (issue 17): built-in height fields for the shapes architects actually build,
// beside the analytic ones of surface_generators.cc (dome on a square plan, hypar, barrel).
// Each takes surface.width (x extent), surface.depth (y extent) and surface.rise (height of
// the crown or the relief, m); u = 2x/width and v = 2y/depth are the plan coordinates scaled
// to [-1, 1]. Supports are not part of a surface: examples/corpus/<name>.yaml gives each roof
// the supports it is built with.
#pragma once

#include "geometry/height_field.h"

namespace pqlayout {

// Circular plan of diameter width, paraboloid z = rise (1 − r²/ρ²).
Status DomeCircular(const GeneratorParams& params, HeightField* field);
// Elliptic plan (semi-axes width/2, depth/2), saddle with a wave:
// z = rise (½(u² − v²) + 0.15 sin(π u)(1 − v²)).
Status SaddleElliptic(const GeneratorParams& params, HeightField* field);
// Rectangle springing from three sides (x = ±width/2, y = −depth/2: z = 0) and open as an arch
// on the fourth (y = +depth/2): z = rise (1 − u²)(1 + v)/2.
Status Canopy(const GeneratorParams& params, HeightField* field);
// L-shaped plan (the rectangle without its quadrant x > 0, y > 0; re-entrant corner at the
// origin), a dome centred in the L: z = rise (1 − ((x + w/8)/(0.7 w))² − ((y + d/8)/(0.7 d))²).
Status LShape(const GeneratorParams& params, HeightField* field);
// Rectangle with a circular hole of radius 0.12 min(w, d) at (0.2 w, 0.1 d); a dome with a
// ring ridge around the hole: z = rise b (1 + 0.4 exp(−((ρ − 1.6 r)/(0.5 r))²)), b = (1 − u²)(1 − v²).
Status HoleOffCentre(const GeneratorParams& params, HeightField* field);
// Rectangle with two circular holes (radius 0.1 and 0.08 min(w, d), at (−0.25 w, 0) and
// (0.25 w, 0.05 d)); z = rise (1 − u²)(1 − v²).
Status TwoHoles(const GeneratorParams& params, HeightField* field);
// Rectangle, a freeform of three Gaussian bumps: z = rise Σ a_k exp(−|p − c_k|² / s_k²).
Status Wavy(const GeneratorParams& params, HeightField* field);

}  // namespace pqlayout
