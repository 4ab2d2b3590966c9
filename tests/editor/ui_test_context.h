// The editor's ImGui context for headless UI tests: made as the app makes it
// (editor/ui_context.h), with a stand-in renderer for the font textures, and input fed through
// the same event queue (io.Add*Event) that the GLFW backend feeds.
#pragma once

#include <imgui.h>

#include "editor/ui_context.h"

// The GLFW backend's own translation of a GLFW key code (imgui_impl_glfw.cpp), so tests press
// keys by the codes the window system sends.
ImGuiKey ImGui_ImplGlfw_KeyToImGuiKey(int keycode, int scancode);

namespace glint::test {

inline void start_test_ui(float content_scale, ImVec2 display) {
  create_ui_context(content_scale);
  ImGuiIO& io = ImGui::GetIO();
  io.BackendFlags |= ImGuiBackendFlags_RendererHasTextures;
  io.DisplaySize = display;
  io.DeltaTime = 1.0f / 60;
}

// What a renderer backend does after ImGui::Render(): textures ImGui asks for "exist" (id 1).
inline void settle_test_textures() {
  for (ImTextureData* tex : ImGui::GetPlatformIO().Textures) {
    if (tex->Status == ImTextureStatus_WantCreate || tex->Status == ImTextureStatus_WantUpdates) {
      tex->SetTexID(ImTextureID(1));
      tex->SetStatus(ImTextureStatus_OK);
    } else if (tex->Status == ImTextureStatus_WantDestroy) {
      tex->SetTexID(ImTextureID_Invalid);
      tex->SetStatus(ImTextureStatus_Destroyed);
    }
  }
}

inline ImGuiKey glfw_key(int glfw_code) { return ImGui_ImplGlfw_KeyToImGuiKey(glfw_code, 0); }

// Modifier state as the backend sends it with each key event.
inline void set_modifiers(bool ctrl, bool shift) {
  ImGuiIO& io = ImGui::GetIO();
  io.AddKeyEvent(ImGuiMod_Ctrl, ctrl);
  io.AddKeyEvent(ImGuiMod_Shift, shift);
}

}  // namespace glint::test
