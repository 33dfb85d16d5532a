// gen_env_map: small equirectangular environment maps (Radiance .hdr) that split the sky light
// the cones gather into its parts (tools/cone_light_split.sh,
// bench/results/zen5-2core-pocl-cone-thin-surfaces.md):
//   gen_env_map OUT.hdr const   64x32, radiance 1 everywhere (a furnace sky)
//   gen_env_map OUT.hdr upper   64x32, radiance 1 above the horizon, 0 below (a sky over a
//                               ground that only the scene's own ground can hide)
//   gen_env_map OUT.hdr sun     256x128 of radiance 0.001 and one 2x2-texel sun of 2000 (rows
//                               34-35, columns 100-101: about 41 degrees up), which
//                               `--env-suns` takes out as a directional light: a sun alone
// Rows run from +y (the top row) down, as the renderer reads them (scene/environment.h).
#include <cstdio>
#include <string>
#include <vector>

#include <stb/stb_image_write.h>

namespace {

constexpr const char* kUsage = "usage: gen_env_map OUT.hdr const|upper|sun\n";

std::vector<float> make_map(const std::string& kind, int& w, int& h) {
  w = kind == "sun" ? 256 : 64;
  h = w / 2;
  std::vector<float> rgb(size_t(w) * size_t(h) * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float v = 1.0f;
      if (kind == "upper") v = y < h / 2 ? 1.0f : 0.0f;
      if (kind == "sun") v = (y == 34 || y == 35) && (x == 100 || x == 101) ? 2000.0f : 1.0e-3f;
      for (int c = 0; c < 3; ++c) rgb[(size_t(y) * size_t(w) + size_t(x)) * 3 + size_t(c)] = v;
    }
  return rgb;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const std::string kind = argc == 3 ? argv[2] : "";
  if (argc != 3 || argv[1][0] == '-' || (kind != "const" && kind != "upper" && kind != "sun")) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  int w = 0, h = 0;
  const std::vector<float> rgb = make_map(kind, w, h);
  // Written to a temporary name and renamed, so OUT is whole or absent.
  const std::string out = argv[1], tmp = out + ".tmp";
  if (stbi_write_hdr(tmp.c_str(), w, h, 3, rgb.data()) == 0 ||
      std::rename(tmp.c_str(), out.c_str()) != 0) {
    std::remove(tmp.c_str());
    std::fprintf(stderr, "gen_env_map: cannot write %s\n", out.c_str());
    return 1;
  }
  std::printf("wrote %s: %s, %dx%d\n", out.c_str(), kind.c_str(), w, h);
  return 0;
}
