// The editor's UI driven headlessly, the fixture of tests/editor/ui_*_test.cpp: an ImGui
// context and a headless EGL context, no window. Panels run for real frames (editor_frame, as
// the app runs them) with simulated mouse and keys; the viewport traces for real.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include <epoxy/gl.h>
// epoxy must come before GLFW.
#define GLFW_INCLUDE_NONE  // key codes only; GL comes from epoxy
#include <GLFW/glfw3.h>  // key codes (translated as the GLFW backend translates them)

#include <imgui_internal.h>  // FindWindowByName: where a popup's buttons are

#include "editor/editor_frame.h"
#include "editor/picking.h"
#include "editor/ui.h"
#include "editor/viewport_renderer.h"
#include "renderer/gl_context.h"
#include "ui_test_context.h"

namespace glint::test {

inline const std::filesystem::path kProjects = std::filesystem::path(GLINT_SOURCE_DIR) / "projects";

class UiTest : public ::testing::Test {
 protected:
  void SetUp() override {
    gl_ = HeadlessGLContext::create();
    start_imgui();
    viewport_ = std::make_unique<ViewportRenderer>();
    state_.viewport.resolution = ViewportResolution::quarter;  // tiny GL images
    state_.flow.projects_dir = kProjects;
    open_document(doc_, state_, kProjects / "default.glint");
    frame();
    frame();  // the default dock layout is in place from the second frame
  }
  void TearDown() override {
    state_.thumbnails.clear();
    viewport_.reset();
    destroy_ui_context();
  }

  // A fresh ImGui context, as at the editor's start: no window exists before its first frame.
  void start_imgui() {
    test::start_test_ui(1, ImVec2(800, 500));
  }

  // One UI frame, as the app runs it.
  void frame() {
    ImGui::NewFrame();
    // Popups are opened at the root of the ID stack, where a frame starts.
    unsaved_prompt_open_ = ImGui::IsPopupOpen("Unsaved changes");
    path_prompt_open_ = ImGui::IsPopupOpen("Choose a file");
    error_open_ = ImGui::IsPopupOpen("Error");
    recovery_offer_open_ = ImGui::IsPopupOpen("Recover unsaved work?");
    editor_frame(doc_, state_, *viewport_);
    test::settle_test_textures();
  }
  // A GLFW key pressed in one frame and released in the next (queued as the backend does).
  void press(int key, bool ctrl = false, bool shift = false) {
    ImGuiIO& io = ImGui::GetIO();
    test::set_modifiers(ctrl, shift);
    io.AddKeyEvent(test::glfw_key(key), true);
    frame();
    io.AddKeyEvent(test::glfw_key(key), false);
    test::set_modifiers(false, false);
    frame();
  }
  void mouse_to(ImVec2 at) { ImGui::GetIO().AddMousePosEvent(at.x, at.y); }
  void mouse_button(bool down) { ImGui::GetIO().AddMouseButtonEvent(0, down); }
  // Screen position of a world point in the viewport.
  ImVec2 screen(glm::vec3 p) {
    glm::vec2 v;
    EXPECT_TRUE(project_to_viewport(shown_scene().camera, {state_.viewport.size.x, state_.viewport.size.y}, p, v));
    return ImVec2(state_.viewport.pos.x + v.x, state_.viewport.pos.y + v.y);
  }
  void click(ImVec2 at, bool ctrl = false) {
    mouse_to(at);
    frame();
    test::set_modifiers(ctrl, false);
    mouse_button(true);
    frame();
    mouse_button(false);
    frame();
    test::set_modifiers(false, false);
  }
  // Where an item of `window` (its ID there, e.g. GetID(label)) is hovered, scanning down a column
  // `x_offset` in from the window's left; (-1, -1) when it is not.
  ImVec2 find_item(const char* window, ImGuiID id, float x_offset = 60) {
    ImGuiWindow* w = ImGui::FindWindowByName(window);
    if (!w) return ImVec2(-1, -1);
    for (float y = w->Pos.y + 4; y < w->Pos.y + w->Size.y; y += 6) {
      const ImVec2 at(w->Pos.x + x_offset, y);
      mouse_to(at);
      frame();
      if (ImGui::GetCurrentContext()->HoveredId == id) return at;
    }
    return ImVec2(-1, -1);
  }
  ImVec2 find_item(const char* window, const char* label, float x_offset = 60) {
    ImGuiWindow* w = ImGui::FindWindowByName(window);
    return w ? find_item(window, w->GetID(label), x_offset) : ImVec2(-1, -1);
  }
  // Text typed as the GLFW backend sends it: each character's key and the character itself.
  void type(const std::string& text) {
    ImGuiIO& io = ImGui::GetIO();
    for (char c : text) {
      ImGuiKey key = c == '-' ? ImGuiKey_Minus : c == '.' ? ImGuiKey_Period
                   : c >= '0' && c <= '9' ? ImGuiKey(ImGuiKey_0 + (c - '0')) : ImGuiKey_None;
      if (key != ImGuiKey_None) io.AddKeyEvent(key, true);
      io.AddInputCharacter(static_cast<unsigned>(c));
      frame();
      if (key != ImGuiKey_None) io.AddKeyEvent(key, false);
      frame();
    }
  }
  // Centre of button `n` (each `width` wide) in the last row of the auto-sized popup `name`.
  ImVec2 popup_button(const char* name, int n, float width) {
    ImGuiWindow* w = ImGui::FindWindowByName(name);
    EXPECT_NE(w, nullptr) << name;
    if (!w) return ImVec2(0, 0);
    const ImGuiStyle& style = ImGui::GetStyle();
    return ImVec2(w->Pos.x + style.WindowPadding.x + n * (width + style.ItemSpacing.x) + width / 2,
                  w->Pos.y + w->Size.y - style.WindowPadding.y - ImGui::GetFrameHeight() / 2);
  }
  // The scene as the viewport traces it: the camera widened to frame the film.
  Scene shown_scene() {
    Scene s = doc_.scene;
    s.camera = shown_camera(doc_.scene, {state_.viewport.size.x, state_.viewport.size.y});
    return s;
  }
  // The status bar's text (all its pieces).
  std::string status_text() {
    std::string text;
    for (const StatusPiece& p : status_line(state_, ImGui::GetTime())) text += p.text;
    return text;
  }
  // The sphere whose centre shows nearest the middle of the viewport (and picks as itself).
  int visible_sphere() {
    int best = -1;
    float best_d = 1e30f;
    for (size_t i = 0; i < doc_.scene.spheres.size(); ++i) {
      glm::vec2 v;
      const Scene shown = shown_scene();
      if (!project_to_viewport(shown.camera, {state_.viewport.size.x, state_.viewport.size.y},
                               doc_.scene.spheres[i].center, v))
        continue;
      glm::vec2 film = v / glm::vec2(state_.viewport.size.x, state_.viewport.size.y);
      auto hit = pick(shown, film, state_.viewport.size.x / state_.viewport.size.y);
      float d = glm::length(film - glm::vec2(0.5f));
      if (hit && hit->what == Selection{SelectionKind::sphere, int(i)} && d < best_d) {
        best = int(i);
        best_d = d;
      }
    }
    return best;
  }

  std::unique_ptr<HeadlessGLContext> gl_;
  std::unique_ptr<ViewportRenderer> viewport_;
  Document doc_;
  EditorState state_;
  bool unsaved_prompt_open_ = false, path_prompt_open_ = false, error_open_ = false, recovery_offer_open_ = false;
};

}  // namespace glint::test
