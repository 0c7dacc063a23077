#include "hud_renderer.hpp"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <filesystem>

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
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0F;
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    return hal::make_error(StatusCode::not_supported, "ImGui: OpenGL 3 back end did not start");
  }
  backend_ = true;
  return {};
}

void HudRenderer::draw(const HudText& text, int width, int height, double delta_s) {
  if (!backend_) return;
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = static_cast<float>(std::clamp(delta_s, 1e-4, 1.0));
  // An auto-sized ImGui window takes one frame to measure itself and shows nothing
  // meanwhile; a snapshot is a single frame: lay a changed text out once unseen.
  std::size_t longest = 0;
  for (const std::string& line : text.lines) longest = std::max(longest, line.size());
  const std::array<std::size_t, 6> layout{text.lines.size(),  longest,
                                          text.banner.size(), text.detail.size(),
                                          std::size_t(width), std::size_t(height)};
  if (layout != layout_) {
    layout_ = layout;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    build(text);
    ImGui::EndFrame();
  }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  build(text);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void HudRenderer::build(const HudText& text) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(8.0F, 8.0F));
  ImGui::SetNextWindowBgAlpha(0.55F);
  ImGui::Begin("hud", nullptr, kFixed);
  ImGui::PushFont(text_font_);
  for (const std::string& line : text.lines) ImGui::TextUnformatted(line.c_str());
  ImGui::PopFont();
  const ImVec2 pos = ImGui::GetWindowPos();
  const ImVec2 size = ImGui::GetWindowSize();
  panel_[0] = pos.x;
  panel_[1] = pos.y;
  panel_[2] = size.x;
  panel_[3] = size.y;
  ImGui::End();
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

}  // namespace twister::bridge
