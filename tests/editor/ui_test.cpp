// The editor's UI driven headlessly (the fixture: ui_test_fixture.h): selecting, the move
// gizmo, undo, files, the status line, and usability.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <epoxy/gl.h>
// epoxy must come before GLFW.
#define GLFW_INCLUDE_NONE  // key codes only; GL comes from epoxy
#include <GLFW/glfw3.h>  // key codes (translated as the GLFW backend translates them)

#include <imgui_internal.h>  // FindWindowByName: where a popup's buttons are

#include "renderer/render_session.h"
#include "editor/editor_frame.h"
#include "editor/film_frame.h"
#include "editor/picking.h"
#include "editor/recent_and_recovery.h"
#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/viewport_renderer.h"
#include "editor_test_util.h"
#include "ui_test_context.h"
#include "ui_test_fixture.h"
#include "renderer/gl_context.h"
#include "renderer/project_file.h"
#include "tests/image_fixtures.h"

namespace glint {
namespace {
namespace fs = std::filesystem;

using test::kProjects;
using test::UiTest;

TEST_F(UiTest, ViewportAccumulatesAndFillsTheCentre) {
  for (int i = 0; i < 5; ++i) frame();
  EXPECT_GE(state_.viewport.frame.stats.spp, 5);
  EXPECT_NE(state_.viewport.frame.display_texture, 0u);
  EXPECT_EQ(state_.viewport.frame.stats.scene_problem, "");
  EXPECT_GT(state_.viewport.size.x, 100);
  EXPECT_GT(state_.viewport.pos.x, 0);  // outliner on the left
  EXPECT_LT(state_.viewport.pos.x + state_.viewport.size.x, 800);  // properties on the right
  EXPECT_EQ(state_.viewport.frame.stats.trace_width, (int(state_.viewport.size.x) + 3) / 4);
}

// The viewport renders after the widgets, at the panel's size of this very frame, and the image
// ImGui draws is that render: a resized window never shows a stale or stretched frame.
TEST_F(UiTest, ResizeShowsTheImageRenderedForThisFramesSize) {
  for (int i = 0; i < 2; ++i) frame();
  for (ImVec2 display : {ImVec2(1000, 640), ImVec2(700, 420), ImVec2(701, 421)}) {
    ImGui::GetIO().DisplaySize = display;
    frame();
    const ViewportView& v = state_.viewport;
    // The dock space follows the window: the properties panel stays at its right edge.
    const ImGuiWindow* properties = ImGui::FindWindowByName("Properties");
    ASSERT_NE(properties, nullptr);
    EXPECT_NEAR(properties->Pos.x + properties->Size.x, display.x, 0.5f);
    EXPECT_LE(v.pos.x + v.size.x, properties->Pos.x + 0.5f);
    const unsigned tex = v.frame.display_texture;
    ASSERT_NE(tex, 0u);
    // The texture shown is the one traced at this frame's size (quarter resolution here).
    int tw = 0, th = 0;
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &tw);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &th);
    EXPECT_EQ(tw, (int(std::lround(v.size.x)) + 3) / 4) << display.x;
    EXPECT_EQ(th, (int(std::lround(v.size.y)) + 3) / 4) << display.y;
    EXPECT_EQ(v.frame.stats.trace_width, tw);
    // ... and this frame's draw data draws it over exactly the panel.
    int images = 0;
    const ImDrawData* data = ImGui::GetDrawData();
    for (int l = 0; l < data->CmdListsCount; ++l) {
      const ImDrawList* list = data->CmdLists[l];
      for (const ImDrawCmd& cmd : list->CmdBuffer) {
        if (cmd.GetTexID() != static_cast<ImTextureID>(tex)) continue;
        ++images;
        ImVec2 lo(1e9f, 1e9f), hi(-1e9f, -1e9f);
        for (unsigned i = 0; i < cmd.ElemCount; ++i) {
          const ImVec2 p = list->VtxBuffer[cmd.VtxOffset + list->IdxBuffer[cmd.IdxOffset + i]].pos;
          lo = ImVec2(std::min(lo.x, p.x), std::min(lo.y, p.y));
          hi = ImVec2(std::max(hi.x, p.x), std::max(hi.y, p.y));
        }
        EXPECT_NEAR(lo.x, v.pos.x, 0.01f);
        EXPECT_NEAR(lo.y, v.pos.y, 0.01f);
        EXPECT_NEAR(hi.x, v.pos.x + v.size.x, 0.01f);
        EXPECT_NEAR(hi.y, v.pos.y + v.size.y, 0.01f);
      }
    }
    EXPECT_EQ(images, 1) << display.x;
  }
}

TEST_F(UiTest, EditingASphereResetsExposureDoesNot) {
  for (int i = 0; i < 3; ++i) frame();
  GpuRenderer& r = viewport_->renderer();
  const int w = r.width(), h = r.height();
  const int64_t before = r.sample_count();
  ASSERT_GT(before, 0);

  doc_.scene.display.exposure += 1.5f;  // what the exposure slider writes
  SyncResult s = r.sync(shown_scene(), w, h);
  EXPECT_FALSE(s.accumulation_reset);
  EXPECT_TRUE(s.display_changed);
  EXPECT_EQ(r.sample_count(), before);
  frame();  // and through the UI frame: still accumulating
  EXPECT_GT(r.sample_count(), before);
  doc_.scene.display.tonemap = Tonemap::linear;
  int64_t more = r.sample_count();
  frame();
  EXPECT_GT(r.sample_count(), more);

  doc_.scene.spheres[0].radius *= 1.1f;  // what the radius field writes
  s = r.sync(shown_scene(), w, h);
  EXPECT_TRUE(s.accumulation_reset);
  EXPECT_EQ(r.sample_count(), 0);
  doc_.scene.spheres[0].center.x += 0.1f;
  frame();  // the frame syncs (reset) and traces one batch
  EXPECT_LE(r.sample_count(), viewport_->budget().config().max_samples);
}

TEST_F(UiTest, ClickSelectsCtrlClickFocusesEmptyClickDeselects) {
  int ball = visible_sphere();
  ASSERT_GE(ball, 0);
  const Sphere s = doc_.scene.spheres[ball];
  click(screen(s.center));
  EXPECT_EQ(doc_.selection, (Selection{SelectionKind::sphere, ball}));

  float focus_before = doc_.scene.camera.focus_distance;
  // ImGui floors the mouse position: pick where the click really lands.
  const ImVec2 at(std::floor(screen(s.center).x), std::floor(screen(s.center).y));
  click(at, /*ctrl=*/true);
  auto hit = pick(shown_scene(), {(at.x - state_.viewport.pos.x) / state_.viewport.size.x,
                                  (at.y - state_.viewport.pos.y) / state_.viewport.size.y},
                  state_.viewport.size.x / state_.viewport.size.y);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(doc_.scene.camera.focus_distance, focus_distance_for(doc_.scene.camera, hit->point), 1e-3);
  EXPECT_NE(doc_.scene.camera.focus_distance, focus_before);
  EXPECT_EQ(doc_.selection, (Selection{SelectionKind::sphere, ball}));  // focusing keeps the selection

  click(ImVec2(state_.viewport.pos.x + state_.viewport.size.x * 0.5f, state_.viewport.pos.y + 3));  // the sky
  EXPECT_EQ(doc_.selection.kind, SelectionKind::none);
}

TEST_F(UiTest, GizmoDragMovesAlongOneAxisAsOneUndoStep) {
  int ball = visible_sphere();
  doc_.selection = {SelectionKind::sphere, ball};
  frame();
  const glm::vec3 c0 = doc_.scene.spheres[ball].center;
  // Grab the x handle in its middle (the handle is 0.3 of the half view height at its depth).
  const Camera cam = shown_scene().camera;  // the gizmo's size follows the viewport's camera
  float depth = glm::dot(c0 - cam.position, glm::normalize(cam.target - cam.position));
  float len = depth * std::tan(glm::radians(cam.vfov_deg) * 0.5f) * 0.3f;
  ImVec2 a = screen(c0), b = screen(c0 + glm::vec3(len, 0, 0));
  ImVec2 mid((a.x + b.x) / 2, (a.y + b.y) / 2);
  mouse_to(mid);
  frame();
  EXPECT_EQ(state_.tools.gizmo_hover, 0);
  mouse_button(true);
  frame();
  for (int i = 1; i <= 5; ++i) {  // drag along the handle's screen direction, one full length
    mouse_to(ImVec2(mid.x + (b.x - a.x) * i / 5, mid.y + (b.y - a.y) * i / 5));
    frame();
    EXPECT_TRUE(state_.tools.interacting);
  }
  mouse_button(false);
  frame();
  const glm::vec3 c1 = doc_.scene.spheres[ball].center;
  EXPECT_NEAR(c1.x - c0.x, len, len * 0.05f);
  EXPECT_FLOAT_EQ(c1.y, c0.y);
  EXPECT_FLOAT_EQ(c1.z, c0.z);
  press(GLFW_KEY_Z, /*ctrl=*/true);  // the whole drag is one step
  EXPECT_EQ(doc_.scene.spheres[ball].center, c0);
  press(GLFW_KEY_Z, true, /*shift=*/true);
  EXPECT_EQ(doc_.scene.spheres[ball].center, c1);
}

TEST_F(UiTest, DeleteKeyAndUndoRedo) {
  const size_t n = doc_.scene.spheres.size();
  doc_.selection = {SelectionKind::sphere, 0};
  press(GLFW_KEY_DELETE);
  EXPECT_EQ(doc_.scene.spheres.size(), n - 1);
  press(GLFW_KEY_Z, true);
  EXPECT_EQ(doc_.scene.spheres.size(), n);
  press(GLFW_KEY_Z, true, true);
  EXPECT_EQ(doc_.scene.spheres.size(), n - 1);
  EXPECT_TRUE(doc_.dirty());
}

TEST_F(UiTest, AddSphereGlossyMaterialWithColourTexture) {
  doc_.selection = {SelectionKind::sphere, add_sphere(doc_.scene)};
  frame();
  int m = add_material(doc_.scene, MaterialType::glossy);
  doc_.scene.spheres[doc_.selection.index].material = doc_.scene.materials[m].name;
  frame();
  // The texture slot's "File..." with the typed-path fallback: a prompt, then the file applies.
  state_.flow.native_dialogs = false;
  state_.flow.slot_material = m;
  state_.flow.slot_index = 0;
  choose_file(doc_, state_, FilePurpose::texture_slot);
  frame();
  frame();
  EXPECT_TRUE(path_prompt_open_);
  apply_chosen_file(doc_, state_, FilePurpose::texture_slot, (kProjects / "assets/leather_color.png").string());
  press(GLFW_KEY_ESCAPE);  // closes the prompt
  EXPECT_FALSE(path_prompt_open_);
  const Material& mat = doc_.scene.materials[m];
  int t = find_texture(doc_.scene, mat.color_texture);
  ASSERT_GE(t, 0) << "no colour texture assigned: " << state_.messages.error;
  EXPECT_EQ(test::problems(doc_.scene, true), "");
  EXPECT_NE(state_.thumbnails.get(resolve_asset_path(doc_.scene, doc_.scene.textures[t].path)), 0u);
  frame();
  EXPECT_EQ(state_.viewport.frame.stats.scene_problem, "");
  EXPECT_GT(viewport_->renderer().sample_count(), 0);
}

// A texture or environment the project could not load (it decodes only in part, a texel is
// NaN) is refused with the reason when chosen, never added to the scene.
TEST_F(UiTest, ImagesThatCannotLoadAreRefusedWhenChosen) {
  test::TempDir dir;
  test::write_png_with_short_idat(dir / "short.png");
  Image nan_sky{2, 1, {1, 1, 1, 1, 1, std::nanf(""), 1, 1}};
  save_image(dir / "nan.exr", nan_sky);
  const Scene before = doc_.scene;
  state_.flow.slot_material = 0;
  state_.flow.slot_index = 0;
  apply_chosen_file(doc_, state_, FilePurpose::texture_slot, (dir / "short.png").string());
  EXPECT_NE(state_.messages.error.find((dir / "short.png").string() + ": cannot decode image"), std::string::npos)
      << state_.messages.error;
  state_.messages.error.clear();
  apply_chosen_file(doc_, state_, FilePurpose::environment, (dir / "nan.exr").string());
  EXPECT_NE(state_.messages.error.find("environment.texture: cannot read image: " + (dir / "nan.exr").string() +
                              ": texel (1, 0) channel G is nan"),
            std::string::npos)
      << state_.messages.error;
  EXPECT_EQ(doc_.scene, before);
}

TEST_F(UiTest, SaveAsThroughThePromptThenCtrlSThenReopen) {
  test::TempDir dir;
  state_.flow.native_dialogs = false;
  doc_.scene.spheres[0].radius = 0.77f;
  frame();
  EXPECT_TRUE(doc_.dirty());
  // Save As (never Ctrl+S here: that would overwrite the example project).
  save_document(doc_, state_, /*save_as=*/true);
  frame();
  frame();
  EXPECT_TRUE(path_prompt_open_);
  apply_chosen_file(doc_, state_, FilePurpose::save_project_as, (dir / "copy").string());
  press(GLFW_KEY_ESCAPE);
  EXPECT_EQ(doc_.path(), dir / "copy.glint");
  EXPECT_FALSE(doc_.dirty());
  EXPECT_EQ(doc_.window_title().find('*'), std::string::npos);
  // Now Ctrl+S writes the copy.
  doc_.scene.spheres[1].radius = 0.33f;
  frame();
  EXPECT_NE(doc_.window_title().find('*'), std::string::npos);
  press(GLFW_KEY_S, /*ctrl=*/true);
  EXPECT_FALSE(doc_.dirty());
  Scene saved = doc_.scene;
  Document other;
  ASSERT_TRUE(open_document(other, state_, dir / "copy.glint"));
  EXPECT_FLOAT_EQ(other.scene.spheres[0].radius, 0.77f);
  EXPECT_FLOAT_EQ(other.scene.spheres[1].radius, 0.33f);
  EXPECT_EQ(other.scene.spheres, saved.spheres);
  EXPECT_EQ(test::problems(other.scene, true), "");  // asset paths rebased to the new folder
  EXPECT_EQ(state_.flow.recent_files.size(), 0u);  // no recent-file hook set in this test
}

TEST_F(UiTest, UnsavedChangesPromptGuardsTheExamples) {
  const fs::path example = kProjects / "emissive_mirror_glass.glint";
  doc_.scene.spheres[0].radius *= 2;
  frame();
  ASSERT_TRUE(doc_.dirty());
  const Scene edited = doc_.scene;
  request_action(doc_, state_, DocAction::open_example, example);  // File > Examples
  frame();
  frame();
  EXPECT_TRUE(unsaved_prompt_open_);
  EXPECT_EQ(doc_.scene, edited);  // nothing replaced yet
  press(GLFW_KEY_ESCAPE);          // Cancel
  EXPECT_FALSE(unsaved_prompt_open_);
  EXPECT_EQ(doc_.scene, edited);
  // Clean document: the example opens at once, as an untitled copy.
  doc_.undo();
  frame();
  ASSERT_FALSE(doc_.dirty());
  request_action(doc_, state_, DocAction::open_example, example);
  frame();
  EXPECT_EQ(doc_.path(), fs::path());
  EXPECT_EQ(doc_.scene, load_project(example));
  EXPECT_EQ(doc_.window_title().find('*'), std::string::npos);
}

TEST_F(UiTest, OutlinerAndPropertiesRunForEveryKindOfSelection) {
  for (SelectionKind k : {SelectionKind::sphere, SelectionKind::quad, SelectionKind::material,
                          SelectionKind::texture, SelectionKind::environment, SelectionKind::camera}) {
    doc_.selection = {k, 0};
    frame();
    frame();
  }
  state_.export_ui.show = true;
  frame();
  EXPECT_FALSE(doc_.dirty());  // drawing panels edits nothing
  EXPECT_EQ(test::problems(doc_.scene), "");
}

TEST_F(UiTest, ExportFromTheEditorRunsInSlices) {
  test::TempDir dir;
  state_.export_ui.settings.width = 24;
  state_.export_ui.settings.height = 16;
  state_.export_ui.settings.samples = 12;
  state_.export_ui.settings.output = dir / "shot.png";
  state_.export_ui.job = std::make_unique<ExportJob>(doc_.scene, state_.export_ui.settings);
  int frames = 0;
  while (state_.export_ui.job->state() == ExportJob::State::running && frames < 500) {
    frame();
    ++frames;
  }
  EXPECT_EQ(state_.export_ui.job->state(), ExportJob::State::done) << state_.export_ui.job->error();
  EXPECT_TRUE(fs::exists(dir / "shot.png"));
}

// A session that autosaved `doc` and ended without a clean exit (its lock goes, its files stay).
fs::path crashed_session(const Document& doc, const fs::path& dir) {
  Autosave autosave(dir, 0);
  EXPECT_TRUE(autosave.update(doc, 1)) << autosave.last_error();
  return autosave.file();
}

std::vector<Recovery> offered(const fs::path& dir) {
  std::vector<std::string> notes;
  std::vector<Recovery> found = find_recoveries(notes, dir);
  EXPECT_TRUE(notes.empty()) << notes.front();
  return found;
}

// The editor's start while a crashed run's recovery exists, as run_editor does it: a fresh
// context, the command line's project, the offer set before the first frame. The offer must
// open (after the panels: opened before them, Dear ImGui 1.86 aborts) and Recover must make the
// recovered work the open, unsaved document and delete the recovery files.
TEST_F(UiTest, RecoveryOfferAtStartRecovers) {
  test::TempDir dir;
  const fs::path project = kProjects / "default.glint";
  Document crashed(load_project(project), project);
  crashed.scene.spheres[0].radius = 0.123f;
  const fs::path file = crashed_session(crashed, dir.path());

  state_.thumbnails.clear();
  ImGui::DestroyContext();
  start_imgui();
  ASSERT_TRUE(open_document(doc_, state_, project));
  state_.recoveries = offered(dir.path());
  ASSERT_EQ(state_.recoveries.size(), 1u);
  for (int i = 0; i < 4; ++i) frame();
  EXPECT_TRUE(recovery_offer_open_);
  EXPECT_FALSE(doc_.dirty());
  click(popup_button("Recover unsaved work?", 0, 110));
  frame();
  EXPECT_FALSE(recovery_offer_open_);
  EXPECT_TRUE(state_.recoveries.empty());
  EXPECT_EQ(doc_.path(), project);
  EXPECT_TRUE(doc_.dirty());
  EXPECT_FLOAT_EQ(doc_.scene.spheres[0].radius, 0.123f);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(fs::is_empty(dir.path()));  // sidecar and lock file too
  EXPECT_TRUE(doc_.can_undo());  // back to the file as saved
}

// Discard deletes the recovery and keeps the open document. An error box already open (a
// project that failed to open at start) comes first: the offer waits for it to close.
TEST_F(UiTest, RecoveryOfferWaitsForTheErrorBoxAndDiscards) {
  test::TempDir dir;
  Document crashed;
  add_sphere(crashed.scene);
  crashed_session(crashed, dir.path());
  const Scene before = doc_.scene;
  show_error(state_, "some error");
  state_.recoveries = offered(dir.path());
  ASSERT_EQ(state_.recoveries.size(), 1u);
  for (int i = 0; i < 3; ++i) frame();
  EXPECT_TRUE(error_open_);
  EXPECT_FALSE(recovery_offer_open_);
  press(GLFW_KEY_ENTER);  // OK
  frame();
  EXPECT_FALSE(error_open_);
  EXPECT_TRUE(recovery_offer_open_);
  click(popup_button("Recover unsaved work?", 1, 110));
  frame();
  EXPECT_FALSE(recovery_offer_open_);
  EXPECT_TRUE(state_.recoveries.empty());
  EXPECT_TRUE(offered(dir.path()).empty());
  EXPECT_TRUE(fs::is_empty(dir.path()));
  EXPECT_EQ(doc_.scene, before);
  EXPECT_FALSE(doc_.dirty());
}

// Two sessions crashed: both are offered, one after the other. Recovering the first makes it the
// open, unsaved document; the second waits until that is saved (recovering it would replace the
// first's work), then Discard deletes it. Neither is offered by another editor meanwhile.
TEST_F(UiTest, EveryCrashedSessionIsOfferedInTurn) {
  test::TempDir dir;
  Document first, second;
  add_sphere(first.scene);
  add_quad(second.scene);
  const fs::path first_file = crashed_session(first, dir.path());
  const fs::path second_file = crashed_session(second, dir.path());
  fs::last_write_time(second_file, fs::last_write_time(first_file) - std::chrono::hours(1));
  state_.recoveries = offered(dir.path());
  ASSERT_EQ(state_.recoveries.size(), 2u);
  EXPECT_TRUE(offered(dir.path()).empty());  // held by this editor while on offer
  for (int i = 0; i < 3; ++i) frame();
  ASSERT_TRUE(recovery_offer_open_);
  click(popup_button("Recover unsaved work?", 0, 110));  // the newest: `first`
  for (int i = 0; i < 3; ++i) frame();
  EXPECT_EQ(doc_.scene.spheres.size(), first.scene.spheres.size());
  EXPECT_TRUE(doc_.dirty());
  EXPECT_FALSE(fs::exists(first_file));
  EXPECT_FALSE(recovery_offer_open_);  // waits: the recovered work is not saved yet
  ASSERT_EQ(state_.recoveries.size(), 1u);
  EXPECT_TRUE(fs::exists(second_file));

  doc_.save(dir / "recovered.glint");
  for (int i = 0; i < 3; ++i) frame();
  ASSERT_TRUE(recovery_offer_open_);
  click(popup_button("Recover unsaved work?", 1, 110));  // Discard
  frame();
  EXPECT_FALSE(recovery_offer_open_);
  EXPECT_TRUE(state_.recoveries.empty());
  EXPECT_FALSE(fs::exists(second_file));
  EXPECT_EQ(doc_.scene.spheres.size(), first.scene.spheres.size());
}

// Enter on a typed path that fails to open: the error box opens in that frame and must not
// take the same press (nor its repeats while the key is held); a new press closes it.
TEST_F(UiTest, EnterOnAFailedTypedPathShowsTheError) {
  test::TempDir dir;
  const fs::path missing = dir / "missing.glint";
  state_.flow.native_dialogs = false;
  choose_file(doc_, state_, FilePurpose::open_project);
  std::snprintf(state_.flow.prompt.buffer, sizeof state_.flow.prompt.buffer, "%s", missing.c_str());
  for (int i = 0; i < 3; ++i) frame();  // the prompt opens and its field takes the keyboard
  ASSERT_TRUE(path_prompt_open_);
  ImGuiIO& io = ImGui::GetIO();
  io.AddKeyEvent(ImGuiKey_Enter, true);
  for (int i = 0; i < 40; ++i) frame();  // held past the key repeat delay
  io.AddKeyEvent(ImGuiKey_Enter, false);
  frame();
  frame();
  EXPECT_FALSE(path_prompt_open_);
  EXPECT_TRUE(error_open_);
  EXPECT_NE(state_.messages.error.find(missing.string()), std::string::npos) << state_.messages.error;
  EXPECT_EQ(doc_.path(), kProjects / "default.glint");  // the open document stays
  press(GLFW_KEY_ENTER);
  frame();
  EXPECT_FALSE(error_open_);
}

// The status line shows the estimated error once the viewport has samples; with a target error
// (the Sampling section's field) the accumulation pauses when the estimate reaches it, and the
// status line says so.
TEST_F(UiTest, StatusLineShowsTheEstimatedErrorAndPausesAtTheTarget) {
  for (int i = 0; i < 200 && state_.viewport.frame.stats.spp < 2; ++i) frame();
  frame();
  std::string text = status_text();
  ASSERT_GE(state_.viewport.frame.stats.spp, 2);
  EXPECT_NE(text.find("est. relMSE "), std::string::npos) << text;
  EXPECT_EQ(text.find("paused"), std::string::npos) << text;
  const double estimate = state_.viewport.frame.stats.estimated_relmse;
  EXPECT_GT(estimate, 0);
  // A target above any estimate the default project has at 16 spp: reached at 16 spp or soon
  // after, then no more samples.
  state_.viewport.target_error = 1e6;
  for (int i = 0; i < 400 && !state_.viewport.frame.stats.target_reached; ++i) frame();
  ASSERT_TRUE(state_.viewport.frame.stats.target_reached);
  const int64_t paused_at = state_.viewport.frame.stats.spp;
  EXPECT_GE(paused_at, kErrorTargetMinSamples);
  for (int i = 0; i < 5; ++i) frame();
  EXPECT_EQ(state_.viewport.frame.stats.spp, paused_at);
  text = status_text();
  EXPECT_NE(text.find("reached: paused"), std::string::npos) << text;
  // Clearing the target resumes.
  state_.viewport.target_error = 0;
  for (int i = 0; i < 5; ++i) frame();
  EXPECT_GT(state_.viewport.frame.stats.spp, paused_at);
}

// A failing autosave (its state folder cannot be made: a file is in the way) shows in the status
// line until an autosave succeeds.
TEST_F(UiTest, AutosaveFailureShowsInTheStatusLine) {
  test::TempDir dir;
  std::ofstream(dir / "blocker") << "a file where the state folder's parent should be";
  state_.autosave.emplace(dir / "blocker" / "glint", /*interval_s=*/0);
  doc_.scene.spheres[0].radius *= 2;
  frame();
  EXPECT_FALSE(state_.autosave->update(doc_, 1));
  const std::string error = state_.autosave->last_error();
  ASSERT_NE(error, "");
  EXPECT_NE(error.find("recovery"), std::string::npos) << error;
  for (int i = 0; i < 3; ++i) frame();
  show_message(state_, "Opened something");  // a transient message does not hide it
  frame();
  std::string text = status_text();
  EXPECT_NE(text.find("autosave failed: " + error), std::string::npos) << text;
  EXPECT_NE(text.find("Opened something"), std::string::npos) << text;

  fs::remove(dir / "blocker");
  EXPECT_TRUE(state_.autosave->update(doc_, 2));
  frame();
  text = status_text();
  EXPECT_EQ(text.find("autosave failed"), std::string::npos) << text;
  EXPECT_TRUE(fs::exists(state_.autosave->file()));
}

// Problems with the editor's own files show in the status line, joined while one shows, beside
// the transient message (which does not hide them).
TEST_F(UiTest, StateFileNotesShowInTheStatusLine) {
  show_note(state_, "/cfg/recent.json: is a FIFO, not a regular file; the recent-files list is empty for now");
  show_message(state_, "Opened something");
  show_note(state_, "/cfg/layout.ini: is a folder, not a regular file; using the default layout");
  frame();
  const std::string text = status_text();
  EXPECT_NE(text.find("the recent-files list is empty for now; /cfg/layout.ini: is a folder"), std::string::npos)
      << text;
  EXPECT_NE(text.find("Opened something"), std::string::npos) << text;
}

// ---- Usability: the automatic preview, the film frame, deleting, dropping files.

class UiUsabilityTest : public UiTest {
 protected:
  const FrameStats& stats() const { return state_.viewport.frame.stats; }
  bool window_active(const char* name) {
    ImGuiWindow* w = ImGui::FindWindowByName(name);
    return w && w->Active;
  }
  void set_budget(double idle_delay, double idle_trace, int refine_min_samples) {
    FrameBudgetConfig c = viewport_->budget().config();
    c.idle_delay_seconds = idle_delay;
    c.idle_trace_seconds = idle_trace;
    c.refine_min_samples = refine_min_samples;
    viewport_->budget().set_config(c);
  }
};

TEST_F(UiUsabilityTest, AutoPreviewKeepsAccumulatingWhileTheExposureIsDragged) {
  // No idle refinement (its restarts are deliberate and tested below): any restart here would
  // be the exposure's.
  set_budget(0.3, 0.25, 1 << 30);
  state_.viewport.resolution = ViewportResolution::automatic;  // the default mode
  doc_.selection = {SelectionKind::sphere, 0};  // a short panel: Display near its top
  frame();
  const ImVec2 at = find_item("Properties", "Exposure");
  ASSERT_GE(at.x, 0) << "the Exposure slider was not found";
  EXPECT_TRUE(window_active("##Tooltip_00")) << "no tooltip on the Exposure slider";
  ImGuiIO& io = ImGui::GetIO();
  const float exposure = doc_.scene.display.exposure;
  mouse_button(true);
  frame();
  const int64_t before = stats().spp;
  const int width = stats().trace_width;
  int64_t last = before;
  for (int i = 0; i < 20; ++i) {
    mouse_to(ImVec2(io.MousePos.x + 3, io.MousePos.y));
    frame();
    EXPECT_FALSE(stats().restarted) << "frame " << i;
    EXPECT_GE(stats().spp, last) << "frame " << i;
    EXPECT_EQ(stats().trace_width, width) << "frame " << i;
    last = stats().spp;
  }
  EXPECT_NE(doc_.scene.display.exposure, exposure);
  // It traces on during the drag, unless the level is finer than a fluid frame allows, where
  // it pauses (keeping every sample) until the mouse is released.
  const bool paused = viewport_->preview().divisor() < viewport_->budget().divisor();
  EXPECT_TRUE(last > before || paused) << before << " -> " << last;
  mouse_button(false);
  for (int i = 0; i < 3; ++i) frame();
  EXPECT_GT(stats().spp, before);
}

TEST_F(UiUsabilityTest, AutoPreviewRefinesToFullResolutionWhenIdle) {
  // Refine at once while a pass fits 1 s (llvmpipe in this small viewport): the end state counts.
  set_budget(0, 1, 1);
  ImGui::GetIO().DisplaySize = ImVec2(640, 400);
  state_.viewport.resolution = ViewportResolution::automatic;
  mouse_to(ImVec2(-1, -1));  // no input at all
  frame();
  EXPECT_GT(stats().divisor, 1);  // it starts coarse
  for (int i = 0; i < 40 && stats().divisor > 1; ++i) frame();
  EXPECT_EQ(stats().divisor, 1);
  EXPECT_EQ(stats().trace_width, int(std::lround(state_.viewport.size.x * state_.viewport.framebuffer_scale)));
  EXPECT_EQ(stats().trace_height, int(std::lround(state_.viewport.size.y * state_.viewport.framebuffer_scale)));
  const int64_t spp = stats().spp;
  frame();
  EXPECT_GT(stats().spp, spp);  // and accumulates there
}

TEST_F(UiUsabilityTest, AutoPreviewClicksThatEditNothingDoNotRestart) {
  set_budget(0.3, 0.25, 1 << 30);  // no idle refinement: any restart would be the clicks'
  state_.viewport.resolution = ViewportResolution::automatic;
  for (int i = 0; i < 3; ++i) frame();
  const int ball = visible_sphere();
  ASSERT_GE(ball, 0);
  const ImVec2 targets[] = {screen(doc_.scene.spheres[ball].center),  // selects
                            // the sky, clear of the dock splitters, of the gizmo's buttons (top left)
                            // and of the region and error-map buttons (top right)
                            ImVec2(state_.viewport.pos.x + state_.viewport.size.x - 15, state_.viewport.pos.y + 60)};
  int64_t last = stats().spp;
  for (ImVec2 target : targets)
    for (int step = 0; step < 3; ++step) {
      mouse_to(target);
      mouse_button(step == 1);
      frame();
      EXPECT_FALSE(stats().restarted) << "step " << step;
      EXPECT_GE(stats().spp, last);
      last = stats().spp;
    }
  EXPECT_EQ(doc_.selection.kind, SelectionKind::none);  // the second click deselected
}

TEST_F(UiUsabilityTest, ViewportFramesTheFilmAndFramesTheSelectionWithMargin) {
  // The test's viewport is portrait, the default film 960x540: letterboxed.
  const glm::vec2 size(state_.viewport.size.x, state_.viewport.size.y);
  ASSERT_LT(size.x / size.y, float(doc_.scene.film.width) / doc_.scene.film.height);
  const FilmRect r = film_rect(size, doc_.scene.film);
  EXPECT_GT(r.offset.y, 1);
  // What the viewport traces: the widened camera, so the rect shows the export's view.
  EXPECT_GT(shown_camera(doc_.scene, size).vfov_deg, doc_.scene.camera.vfov_deg);
  const int ball = visible_sphere();
  ASSERT_GE(ball, 0);
  doc_.selection = {SelectionKind::sphere, ball};
  press(GLFW_KEY_F);
  const std::vector<glm::vec2> outline = selection_outline(doc_.scene, doc_.selection, size);
  ASSERT_FALSE(outline.empty());
  EXPECT_EQ(state_.viewport.outline.size(), outline.size());  // drawn this frame
  float top = 1e9f, bottom = -1e9f;
  for (glm::vec2 p : outline) {
    EXPECT_GT(p.x, r.offset.x);
    EXPECT_LT(p.x, r.offset.x + r.size.x);
    top = std::min(top, p.y);
    bottom = std::max(bottom, p.y);
  }
  EXPECT_GT(top, r.offset.y);
  EXPECT_LT(bottom, r.offset.y + r.size.y);
  const float fill = (bottom - top) / r.size.y;
  EXPECT_GT(fill, 0.45f);  // framed, with room around it
  EXPECT_LT(fill, 0.75f);
}

TEST_F(UiUsabilityTest, DeletingAMaterialInUseAsksAndSelectsNothingAfter) {
  const int m = find_material(doc_.scene, doc_.scene.spheres[0].material);
  ASSERT_GE(m, 0);
  const std::string name = doc_.scene.materials[m].name;
  const size_t count = doc_.scene.materials.size();
  ASSERT_FALSE(material_users(doc_.scene, name).empty());
  doc_.selection = {SelectionKind::material, m};
  press(GLFW_KEY_DELETE);
  EXPECT_TRUE(window_active("Delete material?"));
  EXPECT_EQ(doc_.scene.materials.size(), count);  // nothing yet
  press(GLFW_KEY_ESCAPE);
  EXPECT_FALSE(window_active("Delete material?"));
  EXPECT_EQ(doc_.scene.materials.size(), count);
  EXPECT_EQ(doc_.selection, (Selection{SelectionKind::material, m}));
  press(GLFW_KEY_DELETE);
  ASSERT_TRUE(window_active("Delete material?"));
  click(popup_button("Delete material?", 0, 120));
  EXPECT_EQ(find_material(doc_.scene, name), -1);
  // The default project has no neutral material: a grey "default" replaced the deleted one.
  EXPECT_EQ(doc_.scene.materials.size(), count);
  EXPECT_GE(find_material(doc_.scene, "default"), 0);
  const int now = find_material(doc_.scene, doc_.scene.spheres[0].material);
  ASSERT_GE(now, 0);
  EXPECT_TRUE(is_neutral(doc_.scene.materials[now]));
  EXPECT_EQ(doc_.selection.kind, SelectionKind::none);
  press(GLFW_KEY_DELETE);  // a second Delete removes nothing else
  EXPECT_EQ(doc_.scene.materials.size(), count);
  EXPECT_EQ(test::problems(doc_.scene), "");
}

TEST_F(UiUsabilityTest, HelpWindowsAndExportDialogFitWithoutScrolling) {
  state_.show_controls = state_.show_about = true;
  frame();
  frame();
  EXPECT_TRUE(window_active("Controls"));
  EXPECT_TRUE(window_active("About Glint"));
  state_.show_controls = state_.show_about = false;
  test::TempDir dir;
  state_.export_ui.show = true;
  state_.export_ui.settings = default_export_settings(doc_, state_);
  state_.export_ui.settings.output = dir / "shot.png";
  state_.export_ui.settings.width = 48;
  state_.export_ui.settings.height = 27;
  state_.export_ui.settings.samples = 64;
  frame();
  frame();
  ImGuiWindow* w = ImGui::FindWindowByName("Export render");
  ASSERT_NE(w, nullptr);
  EXPECT_FALSE(w->ScrollbarY);
  state_.export_ui.job = std::make_unique<ExportJob>(doc_.scene, state_.export_ui.settings);
  frame();
  frame();
  EXPECT_FALSE(w->ScrollbarY);  // progress, ETA and Cancel show
  EXPECT_GE(w->Size.x, 520);
  for (int i = 0; i < 500 && export_running(state_); ++i) frame();
  frame();
  EXPECT_FALSE(w->ScrollbarY);  // and the result
  EXPECT_TRUE(fs::exists(dir / "shot.png"));
}

TEST_F(UiUsabilityTest, DroppedImagesBecomeTexturesOrTheEnvironment) {
  test::TempDir dir;
  test::copy_asset("wood_color.png", dir / "wood.png");
  test::copy_asset("sky.hdr", dir / "sky.hdr");
  {
    std::ofstream(dir / "notes.png") << "not an image";
  }
  // Nothing selected: an image has no material to go to.
  doc_.selection = {};
  EXPECT_EQ(drop_file(doc_, state_, dir / "wood.png"), "");
  frame();
  frame();
  EXPECT_TRUE(error_open_);
  click(popup_button("Error", 0, 90));
  frame();
  EXPECT_FALSE(error_open_);
  // On the selected sphere: its material's colour texture.
  doc_.selection = {SelectionKind::sphere, 0};
  const int m = find_material(doc_.scene, doc_.scene.spheres[0].material);
  EXPECT_NE(drop_file(doc_, state_, dir / "wood.png"), "");
  const int t = find_texture(doc_.scene, doc_.scene.materials[m].color_texture);
  ASSERT_GE(t, 0);
  EXPECT_EQ(fs::path(resolve_asset_path(doc_.scene, doc_.scene.textures[t].path)).filename(), "wood.png");
  // .hdr: the environment.
  EXPECT_NE(drop_file(doc_, state_, dir / "sky.hdr"), "");
  EXPECT_EQ(fs::path(doc_.scene.environment.texture).filename(), "sky.hdr");
  // A file that is no image: refused, the scene unchanged.
  const Scene before = doc_.scene;
  EXPECT_EQ(drop_file(doc_, state_, dir / "notes.png"), "");
  EXPECT_EQ(doc_.scene, before);
  frame();
  frame();
  EXPECT_TRUE(error_open_);
  EXPECT_EQ(test::problems(doc_.scene, true), "");
}

TEST_F(UiUsabilityTest, FileChoosersForImagesStartInAFolder) {
  for (FilePurpose p : {FilePurpose::texture_slot, FilePurpose::add_texture, FilePurpose::environment,
                        FilePurpose::open_project}) {
    const std::string start = file_dialog_start(doc_, state_, p);
    EXPECT_EQ(start.back(), '/') << start;
    EXPECT_EQ(start.find("default.glint"), std::string::npos) << start;
  }
  EXPECT_EQ(fs::path(file_dialog_start(doc_, state_, FilePurpose::save_project_as)).filename(), "default.glint");
}

}  // namespace
}  // namespace glint
