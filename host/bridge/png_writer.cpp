#include "png_writer.hpp"

#include <png.h>

#include <csetjmp>
#include <cstdio>

namespace twister::bridge {

hal::Expected<void> write_png(const std::string& path, int width, int height,
                              const std::vector<std::uint8_t>& rgba) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return hal::make_error(StatusCode::io_error, "cannot write " + path);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return hal::make_error(StatusCode::io_error, "cannot write " + path + " (libpng)");
  }
  png_init_io(png, f);
  png_set_compression_level(png, 1);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) {
    png_write_row(png,
                  rgba.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * 4);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(f) != 0) return hal::make_error(StatusCode::io_error, "cannot write " + path);
  return {};
}

}  // namespace twister::bridge
