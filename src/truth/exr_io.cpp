#include "truth/exr_io.h"

#include <exception>
#include <set>
#include <stdexcept>
#include <system_error>

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>

#include "io/atomic_file.h"
#include "io/output_path.h"

namespace rp::truth {
namespace {

constexpr const char* kComponents[3] = {"R", "G", "B"};

// Our own failures, already worded; passed through the handlers that word OpenEXR's.
struct ExrError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string channel_name(const std::string& layer, const char* component) {
  return layer.empty() ? std::string(component) : layer + "." + component;
}

std::string layer_label(const std::string& layer) {
  return layer.empty() ? std::string("'' (R, G, B)") : "'" + layer + "'";
}

// Describes an exception from OpenEXR (Iex::BaseExc is a std::exception in OpenEXR 3; named
// separately so a change of that does not turn its messages into "unknown error").
std::string reason_of(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const Iex::BaseExc& e) {
    return e.what();
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown error";
  }
}

// Slices of 3 interleaved floats per pixel (R, G, B) for one layer; `data` holds the data
// window's pixels, row-major from its top-left corner.
void insert_slices(Imf::FrameBuffer& frame, const std::string& layer, float* data,
                   const Imath::Box2i& window) {
  const size_t x_stride = 3 * sizeof(float);
  const size_t y_stride = x_stride * size_t(window.max.x - window.min.x + 1);
  // OpenEXR addresses pixel (x, y) at base + x * x_stride + y * y_stride, in data window
  // coordinates, so the base is shifted back by the window's origin (0, 0 for our files).
  char* origin = reinterpret_cast<char*>(data);
  const ptrdiff_t shift =
      ptrdiff_t(window.min.x) * ptrdiff_t(x_stride) + ptrdiff_t(window.min.y) * ptrdiff_t(y_stride);
  for (int c = 0; c < 3; ++c)
    frame.insert(channel_name(layer, kComponents[c]),
                 Imf::Slice(Imf::FLOAT, origin - shift + c * sizeof(float), x_stride, y_stride));
}

// Reads the encoded file back and checks that its size and every expected channel are there.
std::string check_written(const std::string& bytes, uint32_t width, uint32_t height,
                          const std::vector<ExrLayer>& layers) {
  Imf::StdISStream stream;
  stream.str(bytes);
  Imf::InputFile in(stream);
  const Imath::Box2i window = in.header().dataWindow();
  if (window.max.x - window.min.x + 1 != int(width) ||
      window.max.y - window.min.y + 1 != int(height))
    return "the file read back has another size";
  const Imf::ChannelList& channels = in.header().channels();
  for (const ExrLayer& layer : layers)
    for (const char* component : kComponents) {
      const Imf::Channel* channel = channels.findChannel(channel_name(layer.name, component));
      if (channel == nullptr || channel->type != Imf::FLOAT)
        return "the file read back lacks channel " + channel_name(layer.name, component);
    }
  return "";
}

}  // namespace

void write_exr_atomic(const std::filesystem::path& path, uint32_t width, uint32_t height,
                      const std::vector<ExrLayer>& layers) {
  const auto fail = [&path](const std::string& reason) {
    return ExrError("cannot write EXR " + path.string() + ": " + reason);
  };
  // OpenEXR's sizes are ints; 16384 x 16384 is the app's limit, far below.
  if (width == 0 || height == 0 || width > (1u << 20) || height > (1u << 20))
    throw fail("image size " + std::to_string(width) + "x" + std::to_string(height));
  if (layers.empty()) throw fail("no layer to write");
  std::set<std::string> names;
  const size_t floats = size_t(width) * height * 3;
  for (const ExrLayer& layer : layers) {
    if (!names.insert(layer.name).second) throw fail("layer " + layer_label(layer.name) + " twice");
    if (layer.rgb == nullptr || layer.rgb->size() != floats)
      throw fail("layer " + layer_label(layer.name) + " does not hold " + std::to_string(width) +
                 "x" + std::to_string(height) + " RGB pixels");
  }

  // Encoded in memory, then written by io::write_file: OpenEXR's own file output buffers in a
  // std::ofstream whose last flush (in its destructor) can fail unseen on a full disk.
  std::string reason, bytes;
  try {
    Imf::Header header{int(width), int(height)};
    header.compression() = Imf::ZIP_COMPRESSION;  // lossless: floats read back bit-exact
    for (const ExrLayer& layer : layers)
      for (const char* component : kComponents)
        header.channels().insert(channel_name(layer.name, component), Imf::Channel(Imf::FLOAT));
    Imf::FrameBuffer frame;
    for (const ExrLayer& layer : layers)
      // OpenEXR's Slice takes a char* for reading and writing alike; writing only reads it.
      insert_slices(frame, layer.name, const_cast<float*>(layer.rgb->data()),
                    header.dataWindow());
    Imf::StdOSStream stream;
    {
      Imf::OutputFile out(stream, header);  // completes the file in its destructor
      out.setFrameBuffer(frame);
      out.writePixels(int(height));
    }
    bytes = stream.str();
    reason = check_written(bytes, width, height, layers);
  } catch (...) {
    reason = reason_of(std::current_exception());
  }
  if (!reason.empty()) throw fail(reason);
  try {
    rp::io::write_file(path, bytes);
  } catch (const rp::io::WriteError& e) {
    throw fail(e.reason());
  }
}

std::vector<float> read_exr_layer(const std::filesystem::path& path, const std::string& layer,
                                  uint32_t& width, uint32_t& height) {
  const auto fail = [&path](const std::string& reason) {
    return ExrError("cannot read EXR " + path.string() + ": " + reason);
  };
  std::string reason;
  try {
    Imf::InputFile in(path.c_str());
    const Imath::Box2i window = in.header().dataWindow();
    const Imf::ChannelList& channels = in.header().channels();
    for (const char* component : kComponents)
      if (channels.findChannel(channel_name(layer, component)) == nullptr) {
        std::set<std::string> present;
        channels.layers(present);
        std::string list = channels.findChannel("R") != nullptr ? "'' (R, G, B)" : "";
        for (const std::string& name : present) list += (list.empty() ? "'" : ", '") + name + "'";
        throw fail("no layer " + layer_label(layer) + " (it has " +
                   (list.empty() ? std::string("none") : list) + ")");
      }
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    if (w <= 0 || h <= 0) throw fail("empty data window");
    std::vector<float> rgb(size_t(w) * size_t(h) * 3);
    Imf::FrameBuffer frame;
    insert_slices(frame, layer, rgb.data(), window);
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);
    width = uint32_t(w);
    height = uint32_t(h);
    return rgb;
  } catch (const ExrError&) {
    throw;
  } catch (...) {
    reason = reason_of(std::current_exception());
  }
  throw fail(reason);
}

}  // namespace rp::truth
