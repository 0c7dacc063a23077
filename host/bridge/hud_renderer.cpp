#include "hud_renderer.hpp"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>

namespace twister::bridge {
namespace {

constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr const char* kBoldFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";

ImFont* add_font(const char* path, float size_px) {
  ImGuiIO& io = ImGui::GetIO();
  if (std::filesystem::exists(path)) {
    if (ImFont* f = io.Fonts->AddFontFromFileTTF(path, size_px)) return f;
  }
  ImFontConfig config;
  config.SizePixels = size_px;
  return io.Fonts->AddFontDefault(&config);
}

constexpr ImGuiWindowFlags kFixed = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs |
                                    ImGuiWindowFlags_NoSavedSettings |
                                    ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                    ImGuiWindowFlags_AlwaysAutoResize;

// The current window's rectangle (pixels, top-left origin): x, y, w, h.
void rectangle(float* r) {
  const ImVec2 pos = ImGui::GetWindowPos();
  const ImVec2 size = ImGui::GetWindowSize();
  r[0] = pos.x;
  r[1] = pos.y;
  r[2] = size.x;
  r[3] = size.y;
}

// One line centred in the current (auto-sized) window.
void centred(const std::string& line) {
  const float width = ImGui::CalcTextSize(line.c_str()).x;
  const float room = ImGui::GetContentRegionAvail().x;
  if (room > width) ImGui::SetCursorPosX(ImGui::GetCursorPosX() + 0.5F * (room - width));
  ImGui::TextUnformatted(line.c_str());
}

}  // namespace

HudRenderer::~HudRenderer() {
  if (context_ == nullptr) return;
  ImGui::SetCurrentContext(context_);
  if (backend_) ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(context_);
}

hal::Expected<void> HudRenderer::init(int height) {
  IMGUI_CHECKVERSION();
  context_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  const float size = std::clamp(static_cast<float>(height) / 48.0F, 12.0F, 28.0F);
  text_font_ = add_font(kFont, size);
  banner_font_ = add_font(kBoldFont, 2.6F * size);
  prompt_font_ = add_font(kFont, 1.5F * size);
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0F;
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    return hal::make_error(StatusCode::not_supported, "ImGui: OpenGL 3 back end did not start");
  }
  backend_ = true;
  return {};
}

void HudRenderer::draw(const HudText& text, int width, int height, double delta_s,
                       const ExhibitText& exhibit) {
  if (!backend_) return;
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = static_cast<float>(std::clamp(delta_s, 1e-4, 1.0));
  // An auto-sized ImGui window takes one frame to measure itself and shows nothing
  // meanwhile; a snapshot is a single frame: lay a changed text out once unseen.
  std::size_t longest = 0;
  for (const std::string& line : text.lines) longest = std::max(longest, line.size());
  std::size_t longest_notice = 0;
  for (const std::string& line : exhibit.notices)
    longest_notice = std::max(longest_notice, line.size());
  const std::array<std::size_t, 9> layout{text.lines.size(),
                                          longest,
                                          text.banner.size(),
                                          text.detail.size(),
                                          std::size_t(width),
                                          std::size_t(height),
                                          exhibit.prompt.size() * 1000 + exhibit.detail.size(),
                                          exhibit.notices.size(),
                                          longest_notice};
  if (layout != layout_) {
    layout_ = layout;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    build(text, exhibit);
    ImGui::EndFrame();
  }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  build(text, exhibit);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void HudRenderer::build(const HudText& text, const ExhibitText& exhibit) {
  const ImGuiIO& io = ImGui::GetIO();
  if (text.lines.empty()) {
    for (float& v : panel_) v = 0.0F;
  } else {
    ImGui::SetNextWindowPos(ImVec2(8.0F, 8.0F));
    ImGui::SetNextWindowBgAlpha(0.55F);
    ImGui::Begin("hud", nullptr, kFixed);
    ImGui::PushFont(text_font_);
    for (const std::string& line : text.lines) ImGui::TextUnformatted(line.c_str());
    ImGui::PopFont();
    rectangle(panel_);
    ImGui::End();
  }
  build_exhibit(exhibit);
  if (!text.banner.empty()) {
    ImGui::SetNextWindowPos(ImVec2(0.5F * io.DisplaySize.x, 0.5F * io.DisplaySize.y),
                            ImGuiCond_Always, ImVec2(0.5F, 0.5F));
    ImGui::SetNextWindowBgAlpha(0.78F);
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.55F, 0.05F, 0.05F, 1.0F));
    ImGui::Begin("banner", nullptr, kFixed);
    ImGui::PushFont(banner_font_);
    ImGui::TextUnformatted(text.banner.c_str());
    ImGui::PopFont();
    ImGui::PushFont(text_font_);
    ImGui::TextUnformatted(text.detail.c_str());
    ImGui::PopFont();
    ImGui::End();
    ImGui::PopStyleColor();
  }
}

// The exhibit's words: the notices centred at the top (a calm blue strip), the
// visitor's prompt centred in the lower part of the screen, clear of the model.
void HudRenderer::build_exhibit(const ExhibitText& exhibit) {
  const ImGuiIO& io = ImGui::GetIO();
  for (float& v : notices_) v = 0.0F;
  for (float& v : prompt_) v = 0.0F;
  if (!exhibit.notices.empty()) {
    ImGui::SetNextWindowPos(ImVec2(0.5F * io.DisplaySize.x, 0.04F * io.DisplaySize.y),
                            ImGuiCond_Always, ImVec2(0.5F, 0.0F));
    ImGui::SetNextWindowBgAlpha(0.8F);
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.08F, 0.22F, 0.45F, 1.0F));
    ImGui::Begin("notices", nullptr, kFixed);
    ImGui::PushFont(prompt_font_);
    for (const std::string& line : exhibit.notices) ImGui::TextUnformatted(line.c_str());
    ImGui::PopFont();
    rectangle(notices_);
    ImGui::End();
    ImGui::PopStyleColor();
  }
  if (exhibit.prompt.empty()) return;
  ImGui::SetNextWindowPos(ImVec2(0.5F * io.DisplaySize.x, 0.96F * io.DisplaySize.y),
                          ImGuiCond_Always, ImVec2(0.5F, 1.0F));
  ImGui::SetNextWindowBgAlpha(0.6F);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(18.0F, 10.0F));
  ImGui::Begin("prompt", nullptr, kFixed);
  ImGui::PushFont(banner_font_);
  // A prompt wider than the screen is written smaller, never cut.
  const float wide = ImGui::CalcTextSize(exhibit.prompt.c_str()).x;
  const float room = 0.92F * io.DisplaySize.x - 36.0F;
  if (wide > room) ImGui::SetWindowFontScale(room / wide);
  centred(exhibit.prompt);
  ImGui::SetWindowFontScale(1.0F);
  ImGui::PopFont();
  if (!exhibit.detail.empty()) {
    ImGui::PushFont(prompt_font_);
    centred(exhibit.detail);
    ImGui::PopFont();
  }
  rectangle(prompt_);
  ImGui::End();
  ImGui::PopStyleVar();
}

}  // namespace twister::bridge
