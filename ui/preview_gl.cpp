// The preview's OpenGL drawing. The path is one GL_LINE_STRIP over the start and each
// segment's end; with the last vertex provoking, line i takes segment i's line and kind.
#include "preview_gl.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace gantry::ui {
namespace {

static_assert(sizeof(ToolpathSegment) == 20 && offsetof(ToolpathSegment, line) == 12 &&
                  offsetof(ToolpathSegment, kind) == 16,
              "the shaders read ToolpathSegment as it is laid out");

// Kinds past PathKind's: the overlay's colours.
constexpr std::uint8_t kTable = 3, kGrid = 4, kTool = 5, kAxisX = 6, kAxisY = 7, kAxisZ = 8;
constexpr int kColours = 9;
constexpr float kColour[kColours][3] = {
    {1.00f, 0.62f, 0.10f},  // cut: orange
    {0.35f, 0.70f, 1.00f},  // jog: blue
    {0.35f, 0.90f, 0.35f},  // keypad: green
    {0.75f, 0.75f, 0.75f},  // table outline
    {0.30f, 0.30f, 0.33f},  // grid
    {1.00f, 0.15f, 0.15f},  // tool
    {0.90f, 0.25f, 0.25f},  // X axis
    {0.25f, 0.85f, 0.25f},  // Y axis
    {0.30f, 0.45f, 1.00f},  // Z axis
};

const char* const kVertex = R"(#version 330 core
layout(location = 0) in vec3 pos;
layout(location = 1) in uint line;
layout(location = 2) in uint kind;
uniform mat4 mvp;
uniform uint current_line;
uniform uint hover_line;
uniform bool show_jogs;
uniform vec3 colours[9];
flat out vec3 colour;
flat out uint vline;
void main() {
  gl_Position = mvp * vec4(pos, 1.0);
  bool path = kind < 3u;
  vline = path ? line : 0u;
  colour = colours[min(kind, 8u)];
  if (path && line != 0u && line == current_line) colour = vec3(1.0, 0.2, 1.0);
  else if (path && line != 0u && line == hover_line) colour = vec3(1.0, 1.0, 1.0);
  if (kind == 1u && !show_jogs) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // clipped away
}
)";

const char* const kFragment = R"(#version 330 core
flat in vec3 colour;
out vec4 frag;
void main() { frag = vec4(colour, 1.0); }
)";

const char* const kPickFragment = R"(#version 330 core
flat in uint vline;
out uint frag;
void main() { frag = vline; }
)";

unsigned compile(GLenum type, const char* src) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::runtime_error(fmt::format("preview shader: {}", log));
  }
  return s;
}

unsigned link(const char* fragment) {
  const GLuint p = glCreateProgram();
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
  glAttachShader(p, vs);
  glAttachShader(p, fs);
  glLinkProgram(p);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("preview shader: the program does not link");
  return p;
}

// The vertex layout both buffers share: ToolpathSegment's.
void describe_vertices() {
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(ToolpathSegment), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribIPointer(1, 1, GL_UNSIGNED_INT, sizeof(ToolpathSegment),
                         reinterpret_cast<const void*>(offsetof(ToolpathSegment, line)));
  glEnableVertexAttribArray(2);
  glVertexAttribIPointer(2, 1, GL_UNSIGNED_BYTE, sizeof(ToolpathSegment),
                         reinterpret_cast<const void*>(offsetof(ToolpathSegment, kind)));
}

ToolpathSegment vertex(float x, float y, float z, std::uint8_t kind) {
  return {x, y, z, 0, static_cast<PathKind>(kind)};
}

}  // namespace

PreviewGL::PreviewGL() {
  program_ = link(kFragment);
  pick_program_ = link(kPickFragment);
  for (auto [vao, vbo] : {std::pair{&path_vao_, &path_vbo_}, std::pair{&over_vao_, &over_vbo_}}) {
    glGenVertexArrays(1, vao);
    glGenBuffers(1, vbo);
    glBindVertexArray(*vao);
    glBindBuffer(GL_ARRAY_BUFFER, *vbo);
    describe_vertices();
  }
  glBindVertexArray(0);
}

PreviewGL::~PreviewGL() {
  glDeleteProgram(program_);
  glDeleteProgram(pick_program_);
  const GLuint vaos[] = {path_vao_, over_vao_}, buffers[] = {path_vbo_, over_vbo_};
  glDeleteVertexArrays(2, vaos);
  glDeleteBuffers(2, buffers);
  const GLuint fbos[] = {fbo_, pick_fbo_}, textures[] = {color_, pick_tex_},
               depths[] = {depth_, pick_depth_};
  glDeleteFramebuffers(2, fbos);
  glDeleteTextures(2, textures);
  glDeleteRenderbuffers(2, depths);
}

void PreviewGL::set_path(const Toolpath& path) {
  count_ = path.segments.empty() ? 0 : path.segments.size() + 1;
  glBindBuffer(GL_ARRAY_BUFFER, path_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(count_ * sizeof(ToolpathSegment)), nullptr,
               GL_STATIC_DRAW);
  if (count_ == 0) return;
  const ToolpathSegment first{path.start.x(), path.start.y(), path.start.z(), path.segments[0].line,
                              path.segments[0].kind};
  glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof first, &first);
  glBufferSubData(GL_ARRAY_BUFFER, sizeof first,
                  static_cast<GLsizeiptr>(path.segments.size() * sizeof(ToolpathSegment)),
                  path.segments.data());
}

void PreviewGL::ensure_targets(int w, int h) {
  if (w == w_ && h == h_ && fbo_) return;
  w_ = w, h_ = h;
  auto target = [&](GLuint& fbo, GLuint& tex, GLuint& depth, GLint internal, GLenum format,
                    GLenum type) {
    if (!fbo) {
      glGenFramebuffers(1, &fbo);
      glGenTextures(1, &tex);
      glGenRenderbuffers(1, &depth);
    }
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, type, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  };
  target(fbo_, color_, depth_, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
  target(pick_fbo_, pick_tex_, pick_depth_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void PreviewGL::draw(const Eigen::Matrix4f& mvp, const Overlay& o, bool pick) {
  const GLuint p = pick ? pick_program_ : program_;
  glUseProgram(p);
  glUniformMatrix4fv(glGetUniformLocation(p, "mvp"), 1, GL_FALSE, mvp.data());
  glUniform1ui(glGetUniformLocation(p, "current_line"), o.current_line);
  glUniform1ui(glGetUniformLocation(p, "hover_line"), o.hover_line);
  glUniform1i(glGetUniformLocation(p, "show_jogs"), o.show_jogs ? 1 : 0);
  glUniform3fv(glGetUniformLocation(p, "colours"), kColours, &kColour[0][0]);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  if (!pick && over_count_ > 0) {
    glBindVertexArray(over_vao_);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(over_count_));
  }
  if (count_ > 1) {
    glBindVertexArray(path_vao_);
    glDrawArrays(GL_LINE_STRIP, 0, static_cast<GLsizei>(count_));
  }
  glBindVertexArray(0);
  glDisable(GL_DEPTH_TEST);
}

unsigned PreviewGL::render(int w, int h, const Camera& cam, const Overlay& o) {
  ensure_targets(std::max(w, 1), std::max(h, 1));
  last_ = o;
  // The overlay: table outline and grid at Z 0, the axes at the origin, the tool's cross.
  std::vector<ToolpathSegment> v;
  auto line = [&](Eigen::Vector3f a, Eigen::Vector3f b, std::uint8_t kind) {
    v.push_back(vertex(a.x(), a.y(), a.z(), kind));
    v.push_back(vertex(b.x(), b.y(), b.z(), kind));
  };
  const float tx = o.table.x(), ty = o.table.y();
  if (o.grid > 0 && tx / o.grid < 500 && ty / o.grid < 500) {
    for (float x = o.grid; x < tx - 1e-4f; x += o.grid) line({x, 0, 0}, {x, ty, 0}, kGrid);
    for (float y = o.grid; y < ty - 1e-4f; y += o.grid) line({0, y, 0}, {tx, y, 0}, kGrid);
  }
  line({0, 0, 0}, {tx, 0, 0}, kTable);
  line({tx, 0, 0}, {tx, ty, 0}, kTable);
  line({tx, ty, 0}, {0, ty, 0}, kTable);
  line({0, ty, 0}, {0, 0, 0}, kTable);
  const float axis = std::max(tx, ty) * 0.08f;
  line({0, 0, 0}, {axis, 0, 0}, kAxisX);
  line({0, 0, 0}, {0, axis, 0}, kAxisY);
  line({0, 0, 0}, {0, 0, axis}, kAxisZ);
  if (o.tool) {
    const Eigen::Vector3f t = *o.tool;
    const float s = o.tool_size;
    line(t - Eigen::Vector3f(s, 0, 0), t + Eigen::Vector3f(s, 0, 0), kTool);
    line(t - Eigen::Vector3f(0, s, 0), t + Eigen::Vector3f(0, s, 0), kTool);
    line(t, t + Eigen::Vector3f(0, 0, 4 * s), kTool);
  }
  over_count_ = v.size();
  glBindBuffer(GL_ARRAY_BUFFER, over_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(ToolpathSegment)),
               v.data(), GL_STREAM_DRAW);

  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, w_, h_);
  glClearColor(0.11f, 0.12f, 0.14f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  draw(cam.projection(static_cast<float>(w_) / static_cast<float>(h_)) * cam.view(), o, false);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return color_;
}

std::uint32_t PreviewGL::pick(int x, int y, const Camera& cam) {
  if (!pick_fbo_ || count_ < 2) return 0;
  glBindFramebuffer(GL_FRAMEBUFFER, pick_fbo_);
  glViewport(0, 0, w_, h_);
  const GLuint zero[4] = {0, 0, 0, 0};
  glClearBufferuiv(GL_COLOR, 0, zero);
  glClear(GL_DEPTH_BUFFER_BIT);
  draw(cam.projection(static_cast<float>(w_) / static_cast<float>(h_)) * cam.view(), last_, true);
  // Lines are one pixel wide: look a few pixels around the pointer, nearest first.
  constexpr int r = 4;
  const int x0 = std::clamp(x - r, 0, w_ - 1), y0 = std::clamp(h_ - 1 - y - r, 0, h_ - 1);
  const int x1 = std::clamp(x + r, 0, w_ - 1), y1 = std::clamp(h_ - 1 - y + r, 0, h_ - 1);
  const int bw = x1 - x0 + 1, bh = y1 - y0 + 1;
  std::vector<GLuint> ids(static_cast<std::size_t>(bw * bh));
  glReadPixels(x0, y0, bw, bh, GL_RED_INTEGER, GL_UNSIGNED_INT, ids.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  std::uint32_t best = 0;
  int best_d = 1 << 30;
  for (int j = 0; j < bh; ++j)
    for (int i = 0; i < bw; ++i) {
      const GLuint id = ids[static_cast<std::size_t>(j * bw + i)];
      const int dx = x0 + i - x, dy = y0 + j - (h_ - 1 - y), d = dx * dx + dy * dy;
      if (id != 0 && d < best_d) best = id, best_d = d;
    }
  return best;
}

}  // namespace gantry::ui
