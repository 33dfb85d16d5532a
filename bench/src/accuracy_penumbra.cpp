// The penumbra's error taken apart (see accuracy_penumbra.h).
#include "bench/src/accuracy_penumbra.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "bench/src/accuracy_metrics.h"

namespace rp::bench {

namespace {

constexpr int kFractionBins = 10;

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

double number_or_nan(const nlohmann::json& v) {
  return v.is_number() ? v.get<double>() : std::nan("");
}

}  // namespace

PenumbraParts penumbra_parts(const std::vector<uint8_t>& penumbra,
                             const std::vector<uint8_t>& floor_material, uint32_t width,
                             uint32_t height) {
  const size_t n = size_t(width) * height;
  if (penumbra.size() != n || floor_material.size() != n)
    throw std::invalid_argument("accuracy: penumbra mask, floor mask and size differ");
  std::vector<uint8_t> not_floor(n);
  for (size_t i = 0; i < n; ++i) not_floor[i] = floor_material[i] ? 0 : 1;
  const std::vector<uint8_t> beside = dilate(not_floor, width, height, 1);
  PenumbraParts parts;
  parts.open_floor.assign(n, 0);
  parts.floor_beside_objects.assign(n, 0);
  parts.objects.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (!penumbra[i]) continue;
    if (!floor_material[i])
      parts.objects[i] = 1;
    else if (beside[i])
      parts.floor_beside_objects[i] = 1;
    else
      parts.open_floor[i] = 1;
  }
  return parts;
}

nlohmann::json penumbra_breakdown(const std::vector<float>& a, const std::vector<float>& truth,
                                  const PenumbraParts& parts,
                                  const std::vector<float>& lamp_fraction) {
  nlohmann::json j;
  const std::pair<const char*, const std::vector<uint8_t>*> named[] = {
      {"open_floor", &parts.open_floor},
      {"floor_beside_objects", &parts.floor_beside_objects},
      {"objects", &parts.objects}};
  for (const auto& [name, mask] : named) {
    uint64_t pixels = 0;
    for (uint8_t m : *mask) pixels += m;
    j["parts"][name] = {{"pixels", pixels},
                        {"direct_psnr_db", number_or_null(masked_tone_mapped_psnr(a, truth, *mask))}};
  }
  const std::vector<ErrorBin> bins =
      tone_mapped_error_by_key(a, truth, parts.open_floor, lamp_fraction, kFractionBins);
  double total = 0.0;
  for (const ErrorBin& b : bins) total += b.squared_sum;
  nlohmann::json list = nlohmann::json::array();
  for (size_t k = 0; k < bins.size(); ++k) {
    const ErrorBin& b = bins[k];
    const bool any = b.pixels > 0;
    list.push_back({{"from", double(k) / kFractionBins},
                    {"to", double(k + 1) / kFractionBins},
                    {"pixels", b.pixels},
                    {"mean", any ? nlohmann::json(b.mean) : nlohmann::json()},
                    {"rms", any ? nlohmann::json(b.rms) : nlohmann::json()},
                    {"share", any && total > 0.0 ? nlohmann::json(b.squared_sum / total)
                                                 : nlohmann::json()}});
  }
  j["open_floor_by_lamp_fraction"] = list;
  return j;
}

std::string penumbra_breakdown_text(const std::string& mode, const nlohmann::json& breakdown) {
  char line[512];
  const nlohmann::json& p = breakdown["parts"];
  std::snprintf(line, sizeof line,
                "%s penumbra by part: open floor %llu px %.2f dB, floor beside objects' "
                "outlines %llu px %.2f dB, objects %llu px %.2f dB\n",
                mode.c_str(), p["open_floor"]["pixels"].get<unsigned long long>(),
                number_or_nan(p["open_floor"]["direct_psnr_db"]),
                p["floor_beside_objects"]["pixels"].get<unsigned long long>(),
                number_or_nan(p["floor_beside_objects"]["direct_psnr_db"]),
                p["objects"]["pixels"].get<unsigned long long>(),
                number_or_nan(p["objects"]["direct_psnr_db"]));
  std::string text = line;
  text += "  open floor by the truth's lamp fraction (tone mapped, real time - truth: mean / rms, "
          "share of the squared error):\n ";
  for (const nlohmann::json& b : breakdown["open_floor_by_lamp_fraction"]) {
    if (b["pixels"].get<uint64_t>() == 0) continue;
    std::snprintf(line, sizeof line, " %.1f-%.1f %+.4f/%.4f %.0f%%", b["from"].get<double>(),
                  b["to"].get<double>(), number_or_nan(b["mean"]), number_or_nan(b["rms"]),
                  100.0 * number_or_nan(b["share"]));
    text += line;
  }
  return text + "\n";
}

}  // namespace rp::bench
