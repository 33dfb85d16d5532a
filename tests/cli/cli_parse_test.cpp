// cli::parse_cli in process: what a command line resolves to, and which lines are usage errors
// (exit code 2) or help (exit code 0), without running anything. The built binary's messages
// are checked end to end in cli_errors_test.cpp and bad_input_test.cpp.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <variant>
#include <vector>

#include "cli/cli.h"

namespace rp::cli {
namespace {

CliParse parse(std::vector<std::string> words) {
  std::vector<const char*> argv = {"rolypoly"};
  for (const std::string& w : words) argv.push_back(w.c_str());
  argv.push_back(nullptr);
  return parse_cli(int(argv.size() - 1), argv.data());
}

ParsedCommand command(const std::vector<std::string>& words) {
  CliParse r = parse(words);
  if (const CliExit* e = std::get_if<CliExit>(&r)) {
    ADD_FAILURE() << "expected a command, got exit " << e->exit_code << ": " << e->message;
    return {};
  }
  return std::get<ParsedCommand>(r);
}

CliExit exit_of(const std::vector<std::string>& words) {
  CliParse r = parse(words);
  if (!std::holds_alternative<CliExit>(r)) {
    ADD_FAILURE() << "expected a usage error or help, got a command";
    return {};
  }
  return std::get<CliExit>(r);
}

TEST(ParseCli, RenderOptionsResolve) {
  ParsedCommand p = command({"render", "--size", "256", "--height", "100", "--frames", "20",
                             "--marbles", "--seed", "9", "--no-taa", "--voxels", "32", "--view",
                             "voxels", "--level", "2", "--dir", "-y", "--out", "d"});
  EXPECT_EQ(p.kind, ParsedCommand::Kind::kRender);
  EXPECT_EQ(p.render.size.width, 256u);
  EXPECT_EQ(p.render.size.height, 100u);
  EXPECT_EQ(p.render.frames, 20u);
  EXPECT_TRUE(p.render.frames_given);
  EXPECT_TRUE(p.render.sim.marbles);
  EXPECT_EQ(p.render.sim.seed, 9u);
  EXPECT_EQ(p.render.out_dir, "d");
  EXPECT_FALSE(p.common.render.effects.taa);
  EXPECT_TRUE(p.common.render.effects.bloom);
  EXPECT_EQ(p.common.render.voxel_resolution, 32u);
  EXPECT_EQ(p.common.view.view, passes::DebugView::kVoxels);
  EXPECT_EQ(p.common.view.level, 2u);
  EXPECT_EQ(p.common.view.dir, 3u);  // -y
  EXPECT_FALSE(command({"render"}).render.frames_given);
}

TEST(ParseCli, IntegersAreDecimalOnly) {
  // CLI11 converts integers with base 0: "0720" would be octal 464, "0x10" sixteen.
  EXPECT_EQ(command({"render", "--size", "0720"}).render.size.width, 720u);
  EXPECT_EQ(command({"run", "--frames", "010"}).run.frames, 10u);
  EXPECT_EQ(exit_of({"render", "--frames", "0x3"}).exit_code, 2);
  EXPECT_EQ(exit_of({"render", "--seed", "-1"}).exit_code, 2);
  EXPECT_EQ(command({"render", "--seed", "18446744073709551615"}).render.sim.seed,
            18446744073709551615u);
  EXPECT_EQ(exit_of({"render", "--seed", "18446744073709551616"}).exit_code, 2);
  const CliExit size = exit_of({"render", "--size", "0"});
  EXPECT_EQ(size.exit_code, 2);
  EXPECT_NE(size.message.find("give 1 to 16384 pixels"), std::string::npos) << size.message;
  EXPECT_EQ(exit_of({"bench", "--sizes", "16,0x20"}).exit_code, 2);
  EXPECT_EQ(command({"bench", "--sizes", "16,032"}).bench.sizes, (std::vector<uint32_t>{16, 32}));
}

TEST(ParseCli, BloomStrengthIsAFiniteFraction) {
  const auto strength = [](const char* value) {
    return command({"render", "--bloom-strength", value}).common.render.effects.bloom_strength;
  };
  EXPECT_FLOAT_EQ(strength("0.25"), 0.25f);
  EXPECT_FLOAT_EQ(strength("1"), 1.0f);
  EXPECT_FLOAT_EQ(command({"render"}).common.render.effects.shutter, 0.5f);
  EXPECT_FLOAT_EQ(command({"run", "--shutter", "0.25"}).common.render.effects.shutter, 0.25f);
  EXPECT_FLOAT_EQ(command({"bench", "--shutter", "1"}).common.render.effects.shutter, 1.0f);
  EXPECT_EQ(exit_of({"render", "--shutter", "1.5"}).exit_code, 2);
  EXPECT_EQ(exit_of({"render", "--quality", "pathtraced", "--shutter", "0.3"}).exit_code, 2);
  for (const char* bad : {"nan", "NaN", "inf", "-0.5", "1.5", "0x1p-1", "0.5x", ""}) {
    const CliExit e = exit_of({"render", "--bloom-strength", bad});
    EXPECT_EQ(e.exit_code, 2) << bad;
    EXPECT_NE(e.message.find("--bloom-strength"), std::string::npos) << e.message;
  }
}

TEST(ParseCli, UsageErrorsAndHelp) {
  const CliExit unknown = exit_of({"paint"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(unknown.message.rfind("rolypoly: unknown subcommand 'paint'", 0), 0u)
      << unknown.message;
  const CliExit level = exit_of({"run", "--view", "albedo", "--level", "1"});
  EXPECT_EQ(level.exit_code, 2);
  EXPECT_NE(level.message.find("--level and --dir choose the volume of --view voxels"),
            std::string::npos);
  EXPECT_EQ(exit_of({"render", "--view", "colour"}).exit_code, 2);
  EXPECT_EQ(exit_of({}).exit_code, 2);
  EXPECT_EQ(exit_of({"bench", "--devices", "all", "--device", "0"}).exit_code, 2);
  EXPECT_EQ(exit_of({"bench", "--sizes", "16", "--size", "32"}).exit_code, 2);
  EXPECT_EQ(exit_of({"bench", "--compare-visibility", "--voxels", "32,64"}).exit_code, 2);
  for (const CliExit& e : {unknown, level})
    EXPECT_NE(e.message.find("Run with --help for more information.\n"), std::string::npos);

  const CliExit help = exit_of({"render", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.message.find("rolypoly render"), std::string::npos) << help.message;
  EXPECT_NE(help.message.find("--bloom-strength"), std::string::npos);
}

TEST(ParseCli, TextureFilterReachesTheCommonOptions) {
  // The default is the renderer's (trilinear: anisotropic costs past the budget).
  EXPECT_EQ(command({"render"}).common.render.texture_filter,
            render::RenderSettings{}.texture_filter);
  EXPECT_EQ(render::RenderSettings{}.texture_filter, render::TextureFilter::kTrilinear);
  EXPECT_EQ(command({"render", "--texture-filter", "bilinear"}).common.render.texture_filter,
            render::TextureFilter::kBilinear);
  EXPECT_EQ(command({"run", "--texture-filter", "anisotropic"}).common.render.texture_filter,
            render::TextureFilter::kAnisotropic);
  EXPECT_EQ(command({"bench", "--texture-filter", "trilinear"}).common.render.texture_filter,
            render::TextureFilter::kTrilinear);
  EXPECT_EQ(exit_of({"bench", "--texture-filter", "box"}).exit_code, 2);
}

// The enum options take exactly the names of their enum's table (render/render_settings.h), in
// every real-time command, and each name reaches the embedded render settings.
template <typename E>
void expect_every_name_reaches(const char* option, E render::RenderSettings::*field) {
  for (const char* sub : {"render", "run", "bench"}) {
    for (const NamedValue<E>& entry : names(E{})) {
      const ParsedCommand p = command({sub, option, std::string(entry.name)});
      EXPECT_EQ(p.common.render.*field, entry.value) << sub << " " << entry.name;
    }
    EXPECT_EQ(exit_of({sub, option, "nonsense"}).exit_code, 2) << sub << " " << option;
  }
}

TEST(ParseCli, EveryNameOfAnEnumOptionReachesTheSettings) {
  expect_every_name_reaches("--visibility", &render::RenderSettings::visibility);
  expect_every_name_reaches("--quality", &render::RenderSettings::quality);
  expect_every_name_reaches("--texture-filter", &render::RenderSettings::texture_filter);
  expect_every_name_reaches("--shadows", &render::RenderSettings::shadows);
  expect_every_name_reaches("--gi-volume", &render::RenderSettings::gi_volume);
}

TEST(ParseCli, PathtracedQualityAndItsOptions) {
  const ParsedCommand defaults = command({"render"});
  EXPECT_FALSE(defaults.common.pathtraced);
  EXPECT_EQ(defaults.common.spp, 256u);
  EXPECT_EQ(defaults.common.render.bounces, 64u) << "all bounces, in every mode";
  EXPECT_FALSE(defaults.render.exr);
  EXPECT_TRUE(command({"render", "--exr"}).render.exr);

  const ParsedCommand p = command({"render", "--quality", "pathtraced", "--spp", "1000000",
                                   "--bounces", "0", "--view", "indirect"});
  EXPECT_TRUE(p.common.pathtraced);
  EXPECT_EQ(p.common.spp, 1000000u);
  EXPECT_EQ(p.common.render.bounces, 0u);
  EXPECT_TRUE(p.render.exr) << "the path-traced frames always come with their EXR";
  EXPECT_EQ(p.common.view.view, passes::DebugView::kIndirect);
  EXPECT_EQ(
      command({"render", "--quality", "pathtraced", "--bounces", "1000"}).common.render.bounces,
      1000u);
  const ParsedCommand b = command({"bench", "--quality", "pathtraced", "--spp", "8", "--json",
                                   "x.json", "--frames", "2"});
  EXPECT_TRUE(b.common.pathtraced);
  EXPECT_EQ(b.common.spp, 8u);
  EXPECT_FALSE(command({"render", "--quality", "reference"}).common.pathtraced);

  for (const std::vector<std::string>& words : std::vector<std::vector<std::string>>{
           {"render", "--spp", "4"}, {"bench", "--spp", "4"},
           {"render", "--quality", "fast", "--spp", "2"}}) {
    const CliExit e = exit_of(words);
    EXPECT_EQ(e.exit_code, 2) << words[1];
    EXPECT_NE(e.message.find("--spp applies to --quality pathtraced"), std::string::npos)
        << e.message;
  }
  EXPECT_EQ(command({"render", "--quality", "pathtraced"}).common.render.bounces, 64u);
  for (const char* bad : {"0", "1000001", "-1", "0x10", "four"})
    EXPECT_EQ(exit_of({"render", "--quality", "pathtraced", "--spp", bad}).exit_code, 2) << bad;
  EXPECT_EQ(exit_of({"render", "--quality", "pathtraced", "--bounces", "1001"}).exit_code, 2);
  const CliExit view = exit_of({"render", "--quality", "pathtraced", "--view", "depth"});
  EXPECT_EQ(view.exit_code, 2);
  EXPECT_NE(view.message.find("--view depth is not available with --quality pathtraced; use "
                              "final, direct, indirect or albedo"),
            std::string::npos)
      << view.message;
  // Options of the OpenCL renderer that cannot apply to the host path tracer.
  for (const char* option : {"--device", "--visibility", "--shadow-size", "--bloom-strength"}) {
    const std::string value = std::string(option) == "--visibility" ? "embree" : "1";
    const CliExit e = exit_of({"render", "--quality", "pathtraced", option, value});
    EXPECT_EQ(e.exit_code, 2) << option;
    EXPECT_NE(e.message.find(std::string(option) + " does not apply to --quality pathtraced"),
              std::string::npos)
        << e.message;
  }
  EXPECT_TRUE(command({"render", "--quality", "pathtraced", "--no-taa"}).common.pathtraced);
  for (const std::vector<std::string>& words : std::vector<std::vector<std::string>>{
           {"--devices", "all"}, {"--sizes", "16,32"}, {"--voxels", "32"},
           {"--compare-visibility"}, {"--quality-report"}, {"--chart", "c.svg"},
           {"--markdown", "m.md"}, {"--scene", "busy"}, {"--device", "0"}}) {
    std::vector<std::string> argv = {"bench", "--quality", "pathtraced"};
    argv.insert(argv.end(), words.begin(), words.end());
    EXPECT_EQ(exit_of(argv).exit_code, 2) << words[0];
  }
  // The window shows real-time frames only.
  EXPECT_EQ(exit_of({"run", "--quality", "pathtraced"}).exit_code, 2);
  EXPECT_EQ(exit_of({"run", "--spp", "4"}).exit_code, 2);
  EXPECT_EQ(exit_of({"run", "--bounces", "0"}).exit_code, 2);
  EXPECT_EQ(exit_of({"run", "--exr"}).exit_code, 2);

  for (const char* sub : {"render", "bench"}) {
    const CliExit help = exit_of({sub, "--help"});
    EXPECT_NE(help.message.find("pathtraced"), std::string::npos) << sub;
    EXPECT_NE(help.message.find("--spp"), std::string::npos) << sub;
  }
  EXPECT_NE(exit_of({"render", "--help"}).message.find("--exr"), std::string::npos);
}

// --shadows (render, run, bench): each name parses to its mode; the default is the renderer's.
TEST(ParseCli, ShadowsInEveryRealTimeCommand) {
  for (const char* sub : {"render", "run", "bench"}) {
    EXPECT_EQ(command({sub}).common.render.shadows, render::RenderSettings{}.shadows) << sub;
    for (render::ShadowMode m : {render::ShadowMode::kHard, render::ShadowMode::kPcf,
                                 render::ShadowMode::kPcss, render::ShadowMode::kVssm}) {
      EXPECT_EQ(command({sub, "--shadows", std::string(name_of(m))}).common.render.shadows, m)
          << sub;
      EXPECT_EQ(parse_name<render::ShadowMode>(std::string(name_of(m))), m);
    }
    EXPECT_EQ(exit_of({sub, "--shadows", "soft"}).exit_code, 2) << sub;
  }
  EXPECT_EQ(render::next_shadow_mode(render::ShadowMode::kVssm), render::ShadowMode::kHard);
  EXPECT_EQ(render::next_shadow_mode(render::ShadowMode::kHard), render::ShadowMode::kPcf);
}

// --bounces applies to every mode of render, run and bench: 1 = single bounce, >= 2 =
// multi-bounce in the real-time modes; 0 only for the path tracer.
TEST(ParseCli, BouncesInEveryMode) {
  for (const char* sub : {"render", "run", "bench"}) {
    EXPECT_EQ(command({sub}).common.render.bounces, 64u) << sub;
    for (const char* quality : {"fast", "reference"}) {
      const auto bounces = [&](const char* n) {
        return command({sub, "--quality", quality, "--bounces", n}).common.render.bounces;
      };
      EXPECT_EQ(bounces("1"), 1u) << sub;
      EXPECT_EQ(bounces("1000"), 1000u) << sub;
      const CliExit zero = exit_of({sub, "--quality", quality, "--bounces", "0"});
      EXPECT_EQ(zero.exit_code, 2) << sub;
      EXPECT_NE(zero.message.find("--bounces 0 applies to --quality pathtraced"),
                std::string::npos)
          << zero.message;
    }
    for (const char* bad : {"1001", "-1", "two", "0x2"})
      EXPECT_EQ(exit_of({sub, "--bounces", bad}).exit_code, 2) << sub << " " << bad;
    const CliExit help = exit_of({sub, "--help"});
    EXPECT_NE(help.message.find("--bounces"), std::string::npos) << sub;
    EXPECT_NE(help.message.find("multi-bounce"), std::string::npos) << sub;
  }
  EXPECT_EQ(command({"bench", "--bounces", "2", "--quality-report"}).common.render.bounces, 2u);
  EXPECT_EQ(command({"bench", "--bounces", "3", "--sizes", "16,32"}).common.render.bounces, 3u);
  EXPECT_EQ(command({"bench", "--bounces", "1", "--compare-visibility"}).common.render.bounces, 1u);
  // bench --accuracy renders both counts itself.
  EXPECT_EQ(exit_of({"bench", "--accuracy", "--bounces", "1"}).exit_code, 2);
}

TEST(ParseCli, AccuracyThresholds) {
  const ParsedCommand p = command({"bench", "--accuracy", "--max-indirect-l1", "0.15",
                                   "--max-indirect-bias", "0.1", "--max-region-bias", "0.15",
                                   "--max-indirect-l1-single", "0.12", "--min-psnr-taa", "30",
                                   "--max-first-frame-gap", "1.5", "--require-wall-hue"});
  EXPECT_TRUE(p.bench.accuracy);
  EXPECT_EQ(p.bench.max_indirect_l1, 0.15);
  EXPECT_EQ(p.bench.max_indirect_bias, 0.1);
  EXPECT_EQ(p.bench.max_region_bias, 0.15);
  EXPECT_EQ(p.bench.max_indirect_l1_single, 0.12);
  EXPECT_EQ(p.bench.min_psnr_taa, 30.0);
  EXPECT_EQ(p.bench.max_first_frame_gap, 1.5);
  EXPECT_TRUE(p.bench.require_wall_hue);
  const ParsedCommand none = command({"bench", "--accuracy"});
  EXPECT_FALSE(none.bench.max_region_bias || none.bench.max_indirect_l1_single ||
               none.bench.min_psnr_taa || none.bench.max_first_frame_gap ||
               none.bench.require_wall_hue);
  for (const char* option : {"--max-region-bias", "--max-indirect-l1-single", "--min-psnr-taa",
                             "--max-first-frame-gap"}) {
    EXPECT_EQ(exit_of({"bench", option, "1"}).exit_code, 2) << option;
    EXPECT_EQ(exit_of({"bench", "--accuracy", option, "inf"}).exit_code, 2) << option;
  }
  const CliExit hue = exit_of({"bench", "--require-wall-hue"});
  EXPECT_EQ(hue.exit_code, 2);
  EXPECT_NE(hue.message.find("belong to --accuracy"), std::string::npos) << hue.message;
  // --truth-noise: a scene file's report (or the half-open demo's under a sky), not the demo's
  const CliExit noise = exit_of({"bench", "--truth-noise"});
  EXPECT_EQ(noise.exit_code, 2);
  EXPECT_NE(noise.message.find("belong to --accuracy"), std::string::npos) << noise.message;
  const CliExit demo_noise = exit_of({"bench", "--accuracy", "--truth-noise"});
  EXPECT_EQ(demo_noise.exit_code, 2);
  EXPECT_NE(demo_noise.message.find("--truth-noise measures a scene file's truth"),
            std::string::npos)
      << demo_noise.message;
  EXPECT_TRUE(command({"bench", "--accuracy", "--truth-noise", "--scene", "yard.glb"})
                  .bench.truth_noise);
}

TEST(ParseCli, BenchKeepsItsCommandLineAndTheSameArgvParsesTheSameTwice) {
  const std::vector<std::string> words = {"bench", "--devices", "all", "--sizes", "256,512",
                                          "--voxels", "32,64", "--scene", "busy"};
  ParsedCommand a = command(words), b = command(words);
  EXPECT_EQ(a.kind, ParsedCommand::Kind::kBench);
  EXPECT_EQ(a.bench.command_line, "rolypoly bench --devices all --sizes 256,512 --voxels 32,64 "
                                  "--scene busy");
  EXPECT_EQ(a.bench.sizes, (std::vector<uint32_t>{256, 512}));
  EXPECT_EQ(a.bench.voxels, (std::vector<uint32_t>{32, 64}));
  EXPECT_EQ(a.bench.scene, "busy");
  EXPECT_EQ(a.bench.command_line, b.bench.command_line);
  EXPECT_EQ(a.bench.sizes, b.bench.sizes);
  EXPECT_EQ(command({"devices"}).kind, ParsedCommand::Kind::kDevices);
}

// Digits past 10^18 saturate before the multiplication could overflow (the CLI fuzzer found a
// signed overflow, undefined behaviour, at 9.3 10^17 x 10): a usage error, nothing else.
TEST(ParseCli, HugeNumbersAreUsageErrorsWithoutOverflow) {
  for (const char* digits :
       {"999999999999999999990720", "930000000000000000", "-99999999999999999999"})
    EXPECT_EQ(exit_of({"render", "--size", digits}).exit_code, 2) << digits;
}

// Every option that takes a value refuses an empty one (--voxels "" became 0, --json ""
// and --record "" wrote nothing, silently). The options come from each subcommand's help, so a
// new option is covered without touching this test.
TEST(ParseCli, EmptyValuesAreUsageErrors) {
  for (const std::string sub : {"render", "run", "bench"}) {
    const std::string help = exit_of({sub, "--help"}).message;
    const std::regex option_with_value("\\n\\s+(--[a-z0-9-]+) [A-Z]");
    int checked = 0;
    for (std::sregex_iterator it(help.begin(), help.end(), option_with_value), end; it != end;
         ++it) {
      const std::string name = (*it)[1];
      for (const std::vector<std::string>& words :
           {std::vector<std::string>{sub, name, ""}, std::vector<std::string>{sub, name + "="}}) {
        const CliExit e = exit_of(words);
        EXPECT_EQ(e.exit_code, 2) << sub << " " << words[1];
        EXPECT_NE(e.message.find(name), std::string::npos) << e.message;
      }
      ++checked;
    }
    EXPECT_GT(checked, 15) << sub << ": the help lists fewer options than expected:\n" << help;
  }
  const CliExit json = exit_of({"bench", "--json", ""});
  EXPECT_EQ(json.message,
            "rolypoly bench: --json needs a value; an empty one is not allowed\n"
            "Run with --help for more information.\n");
  for (const char* list : {"256,,512", ",256", "256,"})
    EXPECT_NE(exit_of({"bench", "--sizes", list}).message.find("--sizes: empty entry in '" +
                                                                std::string(list) + "'"),
              std::string::npos)
        << list;
  EXPECT_EQ(exit_of({"bench", "--voxels=32,,64"}).exit_code, 2);
}

// A device index beyond any device list is a usage error naming the option (it used
// to reach std::stoul and print its bare message "stoul"); a plausible index or a name part
// still parses (whether that device exists is checked once the devices are listed).
TEST(ParseCli, HugeDeviceIndexIsAUsageError) {
  for (const std::string sub : {"render", "run", "bench"}) {
    const CliExit e = exit_of({sub, "--device", "99999999999999999999"});
    EXPECT_EQ(e.exit_code, 2);
    EXPECT_NE(e.message.find("--device: 99999999999999999999 is not a device index"),
              std::string::npos)
        << e.message;
  }
  EXPECT_EQ(command({"render", "--device", "3"}).common.device, "3");
  EXPECT_EQ(command({"render", "--device", "pthread"}).common.device, "pthread");
}

}  // namespace
}  // namespace rp::cli


namespace rp::cli {
namespace {

// --gi-volume: dense by default; svo takes --voxels 256 or 512 (256 when not
// given, also as bench's list); mismatched resolutions and unknown volumes are usage errors
// that say what to use.
TEST(ParseCli, GiVolumeAndItsResolutions) {
  EXPECT_EQ(command({"render"}).common.render.gi_volume, render::GiVolume::kDense);
  const ParsedCommand svo = command({"render", "--gi-volume", "svo", "--voxels", "512"});
  EXPECT_EQ(svo.common.render.gi_volume, render::GiVolume::kSvo);
  EXPECT_EQ(svo.common.render.voxel_resolution, 512u);
  EXPECT_EQ(command({"render"}).common.render.voxel_resolution, 64u);
  EXPECT_EQ(command({"run", "--gi-volume", "svo"}).common.render.voxel_resolution, 256u);
  EXPECT_EQ(command({"bench", "--gi-volume", "svo"}).bench.voxels,
            (std::vector<uint32_t>{256}));
  EXPECT_EQ(command({"bench", "--gi-volume", "svo", "--voxels", "256,512"}).bench.voxels,
            (std::vector<uint32_t>{256, 512}));
  EXPECT_EQ(
      command({"render", "--gi-volume", "dense", "--voxels", "128"}).common.render.gi_volume,
      render::GiVolume::kDense);

  const CliExit dense512 = exit_of({"render", "--voxels", "512"});
  EXPECT_EQ(dense512.exit_code, 2);
  EXPECT_NE(dense512.message.find("--voxels 512 needs --gi-volume svo"), std::string::npos)
      << dense512.message;
  const CliExit svo64 = exit_of({"run", "--gi-volume", "svo", "--voxels", "64"});
  EXPECT_EQ(svo64.exit_code, 2);
  EXPECT_NE(svo64.message.find("--gi-volume svo takes --voxels 256 or 512, not 64"),
            std::string::npos)
      << svo64.message;
  EXPECT_EQ(exit_of({"bench", "--gi-volume", "svo", "--voxels", "256,32"}).exit_code, 2);
  EXPECT_EQ(exit_of({"bench", "--voxels", "64,256"}).exit_code, 2);
  const CliExit unknown = exit_of({"render", "--gi-volume", "octree"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.message.find("--gi-volume"), std::string::npos) << unknown.message;
  EXPECT_EQ(exit_of({"render", "--voxels", "1024"}).exit_code, 2);
  // the path tracer has no GI volume
  EXPECT_EQ(exit_of({"render", "--quality", "pathtraced", "--gi-volume", "svo"}).exit_code, 2);
}

}  // namespace
}  // namespace rp::cli
