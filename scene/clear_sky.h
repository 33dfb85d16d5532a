// A built-in clear sky: the analytic daylight model of Preetham, Shirley and Smits ("A
// Practical Analytic Model for Daylight", SIGGRAPH 1999) rendered into an environment map
// (scene/environment.h's layout and directions), with the matching sun as a directional light.
//
// Sky: luminance Y and chromaticity (x, y) by the Perez distribution
// F(theta, gamma) = (1 + A e^(B / cos theta)) (1 + C e^(D gamma) + E cos^2 gamma), relative to
// the zenith (theta: from the zenith, gamma: from the sun), its coefficients and the zenith's
// values linear in the turbidity T (the paper's appendix); xyY -> XYZ -> linear sRGB (D65).
// Below the horizon the map holds the ground: the horizon's mean colour times ground_albedo.
// Sun: not the paper's spectral sun but a Beer-Lambert stand-in: direct normal illuminance
// 128 klux times exp(-0.1 T m), m the relative air mass (Kasten and Young 1989), in a colour
// that reddens with T m (at 45 degrees and T = 2.5: 90 klux, 64 klux on the ground against the
// model sky's 26 klux; the Preetham sky is known to be brighter towards the horizon than
// measured clear skies, 10-20 klux there). Units: the sky's luminance is in
// kcd/m^2 and the sun's illuminance in klux, both times `scale` into the renderer's radiance
// (a directional light's intensity is irradiance / pi: scene/punctual_light.h).
#pragma once

#include <memory>

#include "scene/environment.h"
#include "scene/frame_scene.h"

namespace rp::scene {

struct ClearSkySettings {
  float sun_azimuth_deg = 135.0f;   // compass angle from -z (the map's left edge) towards +x
  float sun_elevation_deg = 45.0f;  // above the horizon, 1 to 90
  float turbidity = 2.5f;           // 2 (very clear) to 10 (hazy)
  float ground_albedo = 0.3f;
  float scale = 0.01f;              // renderer units per kcd/m^2 (sky) and per klux (sun)
  int width = 512;                  // map width (height = width / 2)
};

struct ClearSky {
  std::shared_ptr<EnvironmentMap> map;
  PunctualLight sun;  // directional, travelling from the sun
};

// Throws std::invalid_argument for settings outside the model's range.
ClearSky make_clear_sky(const ClearSkySettings& settings);

}  // namespace rp::scene
