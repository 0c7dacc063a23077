// MeshRenderer's symmetric program (mesh_shaders.hpp kSymmetricVertex): a live stroke
// under a symmetry group warped in the vertex shader, every image of every hand, from
// the replica's SymmetricLive (per grab: the entries in two texture buffers, per frame:
// the images' constants in a uniform block). GL 3.3 core: texture buffers and uniform
// blocks are core since 3.1. Without them (the program does not build) symmetric
// strokes stay on the CPU path.
#include <epoxy/gl.h>

#include "mesh_renderer.hpp"

namespace twister::bridge {
namespace {

// Texture units and the uniform block's binding point of the symmetric program (the
// other programs and the cue/HUD renderers use unit 0 and no blocks).
constexpr GLint kEntriesUnit = 1;
constexpr GLint kImagesUnit = 2;
constexpr GLuint kImagesBinding = 1;

}  // namespace

void MeshRenderer::init_symmetric(const ShaderSources& sources) {
  hal::Expected<unsigned> program = build_gl_program(sources);
  if (!program) return;  // the CPU path draws symmetric strokes
  const GLuint block = glGetUniformBlockIndex(*program, "Images");
  if (block == GL_INVALID_INDEX) {
    glDeleteProgram(*program);
    return;
  }
  glUniformBlockBinding(*program, block, kImagesBinding);
  symmetric_ = {*program, find_uniforms(*program)};
  sym_entries_loc_ = glGetUniformLocation(*program, "u_entries");
  sym_images_loc_ = glGetUniformLocation(*program, "u_entry_image");
  GLint texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
  max_texels_ = static_cast<std::size_t>(std::max(texels, 0));
  glGenBuffers(static_cast<GLsizei>(sym_buffers_.size()), sym_buffers_.data());
  glGenTextures(static_cast<GLsizei>(sym_textures_.size()), sym_textures_.data());
  glGenBuffers(1, &sym_block_);
  glBindBuffer(GL_UNIFORM_BUFFER, sym_block_);
  glBufferData(
      GL_UNIFORM_BUFFER,
      static_cast<GLsizeiptr>(sizeof(SymmetricImageGpu) * math::SymmetricFloat::kMaxImages),
      nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
}

void MeshRenderer::delete_symmetric() {
  if (symmetric_.id == 0) return;
  glDeleteProgram(symmetric_.id);
  glDeleteBuffers(static_cast<GLsizei>(sym_buffers_.size()), sym_buffers_.data());
  glDeleteTextures(static_cast<GLsizei>(sym_textures_.size()), sym_textures_.data());
  glDeleteBuffers(1, &sym_block_);
  symmetric_ = {};
}

bool MeshRenderer::warps_on_gpu(const LiveState& live) const {
  return !live.cpu_path() || symmetric_fits(live);
}

bool MeshRenderer::symmetric_fits(const LiveState& live) const {
  const SymmetricLive& s = live.symmetric_gpu;
  return symmetric_.id != 0 && allow_symmetric_ && live.method != math::WarpMethod::scodef &&
         live.symmetry.kind != math::SymmetryKind::none && s.ready && s.image_count > 0 &&
         s.spans.size() == 2 * mesh_vertices_ && s.entry_count() <= max_texels_;
}

void MeshRenderer::set_symmetric(const LiveState& live) {
  const SymmetricLive& s = live.symmetric_gpu;
  if (sym_version_ != s.version) {
    // Once per grab: the spans per drawn vertex, the entries and their images (a
    // texture buffer is never empty).
    glBindVertexArray(vao_);
    upload(vbo_[5], drawn(s.spans, 2), 2);
    const std::size_t n = std::max<std::size_t>(s.entry_count(), 1);
    std::vector<float> entries(s.entries);
    std::vector<std::uint8_t> images(s.entry_image);
    entries.resize(4 * n, 0.0F);
    images.resize(n, 0);
    glBindBuffer(GL_TEXTURE_BUFFER, sym_buffers_[0]);
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(entries.size() * sizeof(float)),
                 entries.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, sym_buffers_[1]);
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(images.size()), images.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    glBindTexture(GL_TEXTURE_BUFFER, sym_textures_[0]);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, sym_buffers_[0]);
    glBindTexture(GL_TEXTURE_BUFFER, sym_textures_[1]);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R8UI, sym_buffers_[1]);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    sym_version_ = s.version;
  }
  // Every frame: the images' constants (at most 48 x 80 bytes).
  glBindBuffer(GL_UNIFORM_BUFFER, sym_block_);
  glBufferSubData(GL_UNIFORM_BUFFER, 0,
                  static_cast<GLsizeiptr>(sizeof(SymmetricImageGpu) * s.image_count),
                  s.images.data());
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
}

void MeshRenderer::bind_symmetric() const {
  glActiveTexture(GL_TEXTURE0 + kEntriesUnit);
  glBindTexture(GL_TEXTURE_BUFFER, sym_textures_[0]);
  glActiveTexture(GL_TEXTURE0 + kImagesUnit);
  glBindTexture(GL_TEXTURE_BUFFER, sym_textures_[1]);
  glActiveTexture(GL_TEXTURE0);
  glUniform1i(sym_entries_loc_, kEntriesUnit);
  glUniform1i(sym_images_loc_, kImagesUnit);
  glBindBufferBase(GL_UNIFORM_BUFFER, kImagesBinding, sym_block_);
}

}  // namespace twister::bridge
