// The light from afar that --env FILE / --sky clear ask for (SkyOptions in app/render_session.h),
// made once before the frames and given to every frame: the equirectangular map loaded (or the
// clear sky rendered into one: scene/clear_sky.h) and, for the clear sky, its sun as a
// directional light. The path tracer takes it with every frame (add_sky), the real-time modes
// through RenderSession (which adds it to the frames it renders).
#pragma once

#include <optional>
#include <string>

#include "app/render_session.h"
#include "scene/environment.h"
#include "scene/frame_scene.h"

namespace rp::app {

struct SkyLight {
  scene::Environment environment;           // disabled when neither option was given
  std::optional<scene::PunctualLight> sun;  // --sky clear's sun (strength applied)
};

// Throws scene::AssetError (exit 1) naming the --env file and the system's reason ("--env:
// cannot read environment map sky.hdr: No such file or directory") or the decoder's (a corrupt
// or non-2:1 map, non-finite texels: truth::load_environment_map).
SkyLight load_sky(const SkyOptions& options);

// Gives `frame` the environment and appends the sun to its lights (nothing when none).
void add_sky(const SkyLight& sky, scene::FrameScene& frame);

// Turns the sky about +y by `degrees` (counter-clockwise seen from above, as --env-rotate):
// the map's turn and, for the clear sky, its sun's direction, so the sun stays where the map
// shows it. The turn is kept within (-360, 360).
void turn_sky(SkyLight& sky, float degrees);

// One line for the log, "" when none: "environment: sky.hdr (1024x512), turned 90 degrees,
// strength 2" or "clear sky (Preetham, turbidity 2.5) with its sun at azimuth 135, elevation 45
// degrees".
std::string describe_sky(const SkyOptions& options, const SkyLight& sky);

}  // namespace rp::app
