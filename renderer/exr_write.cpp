// Writing OpenEXR through tinyexr (see exr_io.h): every layer's channels as float32.
#include "renderer/exr_io.h"

#include "renderer/image_file.h"
#include "renderer/image_metadata.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <tinyexr.h>

namespace glint {
namespace {

// One channel of the file: component `component` of `image`'s RGBA.
struct ChannelSource {
  std::string name;
  const Image* image;
  int component;
};

// Every layer's channels, sorted by name as OpenEXR requires.
std::vector<ChannelSource> channel_sources(const std::filesystem::path& path, const std::vector<ExrLayer>& layers) {
  std::vector<ChannelSource> list;
  for (const ExrLayer& layer : layers) {
    const Image& image = *layer.image;
    if (image.width != layers[0].image->width || image.height != layers[0].image->height ||
        image.pixels.size() != static_cast<size_t>(image.width) * image.height * 4)
      image_fail(path, "the layers of an OpenEXR file must have one size");
    if (layer.single_component >= 0) {
      list.push_back({layer.name, &image, std::min(layer.single_component, 3)});
      continue;
    }
    for (size_t c = 0; c < layer.channels.size() && c < 4; ++c)
      list.push_back({(layer.name.empty() ? "" : layer.name + ".") + layer.channels[c], &image, static_cast<int>(c)});
  }
  std::sort(list.begin(), list.end(), [](const ChannelSource& a, const ChannelSource& b) { return a.name < b.name; });
  return list;
}

// The float32 planes and channel descriptions that tinyexr writes from.
struct ChannelPlanes {
  std::vector<std::vector<float>> planes;
  std::vector<unsigned char*> pointers;
  std::vector<EXRChannelInfo> channels;
  std::vector<int> pixel_types;
};

ChannelPlanes channel_planes(const std::filesystem::path& path, const std::vector<ChannelSource>& list, size_t count) {
  const size_t n = list.size();
  ChannelPlanes out{std::vector<std::vector<float>>(n), std::vector<unsigned char*>(n),
                    std::vector<EXRChannelInfo>(n), std::vector<int>(n, TINYEXR_PIXELTYPE_FLOAT)};
  for (size_t c = 0; c < n; ++c) {
    out.planes[c].resize(count);
    for (size_t i = 0; i < count; ++i) out.planes[c][i] = list[c].image->pixels[i * 4 + list[c].component];
    out.pointers[c] = reinterpret_cast<unsigned char*>(out.planes[c].data());
    out.channels[c] = EXRChannelInfo{};
    if (list[c].name.size() >= sizeof out.channels[c].name)
      image_fail(path, "OpenEXR channel name too long: " + list[c].name);
    std::copy(list[c].name.begin(), list[c].name.end(), out.channels[c].name);
  }
  return out;
}

// `attributes` as tinyexr's string attributes (pointing into `attributes`' values).
std::vector<EXRAttribute> string_attributes(const std::filesystem::path& path, const ExrAttributes& attributes) {
  if (attributes.size() > TINYEXR_MAX_CUSTOM_ATTRIBUTES) image_fail(path, "too many OpenEXR attributes");
  std::vector<EXRAttribute> custom(attributes.size());
  for (size_t i = 0; i < attributes.size(); ++i) {
    const auto& [name, value] = attributes[i];
    if (name.size() >= sizeof custom[i].name) image_fail(path, "OpenEXR attribute name too long: " + name);
    std::snprintf(custom[i].name, sizeof custom[i].name, "%s", name.c_str());
    std::snprintf(custom[i].type, sizeof custom[i].type, "string");
    custom[i].value = reinterpret_cast<unsigned char*>(const_cast<char*>(value.data()));
    custom[i].size = static_cast<int>(value.size());
  }
  return custom;
}

// Every layer's channels as float32, sorted by name, ZIP compressed unless the image is smaller
// than 16x16; `attributes` are written as string attributes.
std::vector<unsigned char> encode_exr_layers(const std::filesystem::path& path, const std::vector<ExrLayer>& layers,
                                             const ExrAttributes& attributes = {}) {
  const std::vector<ChannelSource> list = channel_sources(path, layers);
  const int width = layers[0].image->width, height = layers[0].image->height;
  ChannelPlanes planes = channel_planes(path, list, static_cast<size_t>(width) * height);
  std::vector<int> requested_types = planes.pixel_types;
  std::vector<EXRAttribute> custom = string_attributes(path, attributes);
  EXRImage exr_image;
  InitEXRImage(&exr_image);
  exr_image.num_channels = static_cast<int>(list.size());
  exr_image.images = planes.pointers.data();
  exr_image.width = width;
  exr_image.height = height;
  EXRHeader header;
  InitEXRHeader(&header);
  header.compression_type = width < 16 && height < 16 ? TINYEXR_COMPRESSIONTYPE_NONE : TINYEXR_COMPRESSIONTYPE_ZIP;
  header.num_channels = static_cast<int>(list.size());
  header.channels = planes.channels.data();
  header.num_custom_attributes = static_cast<int>(custom.size());
  header.custom_attributes = custom.empty() ? nullptr : custom.data();
  header.pixel_types = planes.pixel_types.data();
  header.requested_pixel_types = requested_types.data();
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&exr_image, &header, &memory, &err);
  if (size == 0 || !memory) image_fail(path, "cannot encode the OpenEXR image (" + take_exr_error(err, 0) + ")");
  std::vector<unsigned char> file(memory, memory + size);
  std::free(memory);
  return file;
}

void check_image_to_save(const std::filesystem::path& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * 4)
    image_fail(path, "cannot save an empty or inconsistent image");
}

}  // namespace

// The channels in A, B, G, R order (sorted by name) as tinyexr's SaveEXR writes them and most
// viewers expect.
std::vector<unsigned char> encode_exr(const std::filesystem::path& path, const Image& image,
                                      const ExrAttributes& attributes) {
  return encode_exr_layers(path, {ExrLayer{"", &image, "RGBA"}}, attributes);
}

void save_exr_layers(const std::filesystem::path& path, const std::vector<ExrLayer>& layers,
                     const ImageMetadata& metadata) {
  if (lower_extension(path) != ".exr") image_fail(path, "layers can only be written to an .exr file");
  if (layers.empty() || !layers[0].image || layers[0].image->width <= 0 || layers[0].image->height <= 0)
    image_fail(path, "cannot save an empty or inconsistent image");
  check_image_metadata(path, metadata);
  write_image_file(path, encode_exr_layers(path, layers, metadata));
}

void save_exr(const std::filesystem::path& path, const Image& image, const ExrAttributes& attributes,
              const std::string& alpha_channel) {
  if (lower_extension(path) != ".exr") image_fail(path, "an image with attributes must be an .exr file");
  check_image_to_save(path, image);
  // With `alpha_channel`, the image's alpha goes to a channel of that name (sorted after R, as
  // OpenEXR requires, so a lowercase name) and A is 1.
  std::vector<ExrLayer> layers{{"", &image, "RGBA"}};
  Image opaque;
  if (!alpha_channel.empty()) {
    opaque = image;
    for (size_t i = 3; i < opaque.pixels.size(); i += 4) opaque.pixels[i] = 1.0f;
    layers = {{"", &opaque, "RGBA"}, {alpha_channel, &image, "", 3}};
  }
  write_image_file(path, encode_exr_layers(path, layers, attributes));
}

}  // namespace glint
