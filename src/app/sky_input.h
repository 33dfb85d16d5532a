// The light from afar that --env FILE / --sky clear ask for (SkyOptions in app/render_session.h),
// made once before the frames and given to every frame: the equirectangular map loaded (or the
// clear sky rendered into one: scene/clear_sky.h) and its suns as directional lights: the clear
// sky's sun, or the map's (--env-suns: scene/environment_suns.h, taken out of the map that the
// real-time modes gather). The path tracer takes it with every frame (add_sky), the real-time
// modes through RenderSession (which adds it to the frames it renders).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/render_session.h"
#include "scene/environment.h"
#include "scene/environment_suns.h"
#include "scene/frame_scene.h"

namespace rp::app {

struct SkyLight {
  scene::Environment environment;          // disabled when neither option was given
  std::vector<scene::PunctualLight> suns;  // --sky clear's sun or the map's (strength applied)
  std::vector<scene::EnvironmentSun> map_suns;  // the map's, in its own frame (describe_sky)
};

// Throws scene::AssetError (exit 1) naming the --env file and the system's reason ("--env:
// cannot read environment map sky.hdr: No such file or directory") or the decoder's (a corrupt
// or non-2:1 map, non-finite texels: truth::load_environment_map).
SkyLight load_sky(const SkyOptions& options);

// Gives `frame` the environment and appends the suns to its lights (nothing when none).
// Where the frame's lights leave room (RP_MAX_PUNCTUAL_LIGHTS) for fewer of the map's suns, the
// dimmest go back into the map, for this frame and the ones after (a note on stderr says so).
// The clear sky's sun is appended as it is (the renderer leaves out lights beyond the limit).
void add_sky(SkyLight& sky, scene::FrameScene& frame);

// Turns the sky about +y by `degrees` (counter-clockwise seen from above, as --env-rotate):
// the map's turn and its suns' directions, so a sun stays where the map shows it. The turn is
// kept within (-360, 360).
void turn_sky(SkyLight& sky, float degrees);

// One line for the log, "" when none: "environment: sky.hdr (1024x512), turned 90 degrees,
// strength 2" or "clear sky (Preetham, turbidity 2.5) with its sun at azimuth 135, elevation 45
// degrees"; a map's suns on a second line each ("  sun 1: 59.9 % of the map's light, 4.7
// degrees across, azimuth 215, elevation 7.9: a directional light with shadows").
std::string describe_sky(const SkyOptions& options, const SkyLight& sky);

}  // namespace rp::app
