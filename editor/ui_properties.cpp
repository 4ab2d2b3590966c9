// The properties panel: whatever is selected (sphere, quad, material, texture, environment,
// camera), and below it the display settings, which only re-run the tonemap pass.
#include <cfloat>
#include <cstdio>

#include "renderer/material_types.h"
#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "editor/ui_tip.h"
#include "renderer/scene_fields.h"
#include "renderer/texture_slots.h"

namespace glint {
namespace {

constexpr ImGuiSliderFlags kClamp = ImGuiSliderFlags_AlwaysClamp;
// Numbers are drag fields, never sliders: a click without a drag types a value (Blender's way,
// io.ConfigDragClickToInputText), where a slider would jump to the clicked position.

// The widgets below are made by hand: a field added to a table of renderer/scene_fields.h
// fails to compile here until the panel has a widget for it (or says why not).
static_assert(field_count<Camera>() == 6 && field_count<Film>() == 2 &&
                  field_count<RenderSettings>() == 2 && field_count<DisplaySettings>() == 2 &&
                  field_count<Environment>() == 4 && field_count<Texture>() == 2 &&
                  field_count<Material>() == 10 && field_count<Sphere>() == 4 &&
                  field_count<Quad>() == 4,
              "a new scene field needs its widget in the properties panel");

// ImGui 1.86 has no SeparatorText.
void section_title(const char* text) {
  ImGui::Spacing();
  ImGui::TextColored(ImVec4(0.55f, 0.75f, 1.0f, 1.0f), "%s", text);
  ImGui::Separator();
}

ImTextureID tex_id(unsigned t) { return static_cast<ImTextureID>(t); }

void name_field(Document& doc, EditorState& state, Selection sel) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s", name_of(doc.scene, sel).c_str());
  const bool entered = ImGui::InputText("Name", buf, sizeof buf, ImGuiInputTextFlags_EnterReturnsTrue);
  tip("The name in the outliner and the project file; Enter renames (references follow).");
  if (entered && !rename(doc.scene, sel, buf))
    show_message(state, std::string("The name '") + buf + "' is empty or taken");
}

// A combo of names; "(none)" first when allow_none. Returns true when changed.
template <typename List>
bool name_combo(const char* label, std::string& value, const List& items, bool allow_none) {
  bool changed = false;
  if (ImGui::BeginCombo(label, value.empty() ? "(none)" : value.c_str())) {
    if (allow_none && ImGui::Selectable("(none)", value.empty())) {
      value.clear();
      changed = true;
    }
    for (const auto& item : items)
      if (ImGui::Selectable(item.name.c_str(), item.name == value)) {
        value = item.name;
        changed = true;
      }
    ImGui::EndCombo();
  }
  return changed;
}

void material_combo(Document& doc, std::string& material) {
  name_combo("Material", material, doc.scene.materials, false);
  tip("The material this object is made of.");
  int m = find_material(doc.scene, material);
  if (m >= 0) {
    ImGui::SameLine();
    if (ImGui::SmallButton("Edit")) doc.selection = {SelectionKind::material, m};
    tip("Select the material to edit it.");
  }
}

// The widgets of one texture slot (renderer/texture_slots.h) of a material.
void texture_slot(Document& doc, EditorState& state, int material, std::string Material::*member) {
  const size_t slot = texture_slot_index(member);
  const TextureSlot& what = kTextureSlots[slot];
  std::string& value = doc.scene.materials[material].*member;
  ImGui::PushID(static_cast<int>(slot));
  int t = find_texture(doc.scene, value);
  unsigned thumb = t >= 0 ? state.thumbnails.get(resolve_asset_path(doc.scene, doc.scene.textures[t].path), 64) : 0;
  if (thumb) ImGui::Image(tex_id(thumb), ImVec2(ui_units(32), ui_units(32)));
  else ImGui::Dummy(ImVec2(ui_units(32), ui_units(32)));
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - ui_units(110));
  name_combo(what.label, value, doc.scene.textures, true);
  tip(what.what);
  const bool file = ImGui::SmallButton("File...");
  tip("Choose an image file for this slot (or drop one on the window).");
  if (file) {
    state.flow.slot_material = material;
    state.flow.slot_index = static_cast<int>(slot);
    choose_file(doc, state, FilePurpose::texture_slot);
  }
  ImGui::EndGroup();
  ImGui::PopID();
}

void sphere_properties(Document& doc, EditorState& state, int i) {
  Sphere& s = doc.scene.spheres[i];
  name_field(doc, state, doc.selection);
  ImGui::DragFloat3("Centre", &s.center.x, 0.01f);
  tip("World position of the centre (drag, or click to type).");
  ImGui::DragFloat("Radius", &s.radius, 0.005f, 1e-4f, 1e6f, "%.4f", kClamp);
  tip("Radius in world units.");
  material_combo(doc, s.material);
}

void quad_properties(Document& doc, EditorState& state, int i) {
  Quad& q = doc.scene.quads[i];
  name_field(doc, state, doc.selection);
  material_combo(doc, q.material);
  section_title("Placement");
  QuadPlacement p = quad_placement(q);
  p.rotation_deg = shown_rotation(state.shown_rotation, i, q);  // as typed, not re-derived
  bool changed = ImGui::DragFloat3("Centre", &p.center.x, 0.01f);
  tip("World position of the quad's centre.");
  changed |= ImGui::DragFloat2("Size", &p.size.x, 0.01f, 1e-3f, 1e6f, "%.3f", kClamp);
  tip("Lengths of the edges p0-p2 (x) and p0-p1 (y).");
  changed |= ImGui::DragFloat3("Rotation", &p.rotation_deg.x, 0.5f, -360, 360, "%.1f deg");
  tip("Orientation as X-Y-Z Euler angles in degrees.");
  if (changed) {
    set_quad_placement(q, p);
    remember_rotation(state.shown_rotation, i, q, p.rotation_deg);
  }
  if (ImGui::TreeNode("Corners")) {
    for (int c = 0; c < 4; ++c) {
      char label[16];
      std::snprintf(label, sizeof label, "p%d", c);
      ImGui::DragFloat3(label, &q.corners[c].x, 0.01f);
      tip("A corner in world coordinates (editing one may make the quad non-rectangular).");
    }
    ImGui::TextDisabled("p3 is opposite p0");
    ImGui::TreePop();
  }
  if (ImGui::TreeNode("Texture coordinates")) {
    for (int c = 0; c < 4; ++c) {
      char label[16];
      std::snprintf(label, sizeof label, "uv%d", c);
      ImGui::DragFloat2(label, &q.uvs[c].x, 0.01f);
      tip("Texture coordinate at this corner.");
    }
    ImGui::TreePop();
  }
}

void material_properties(Document& doc, EditorState& state, int i) {
  Material& m = doc.scene.materials[i];
  name_field(doc, state, doc.selection);
  draw_material_preset_combo(m);
  const MaterialTypeInfo& info = material_type_info(m.type);
  if (ImGui::BeginCombo("Type", info.name)) {
    for (const MaterialTypeInfo& t : kMaterialTypes) {
      if (ImGui::Selectable(t.name, t.type == m.type)) m.type = t.type;
      tip(t.summary);
    }
    ImGui::EndCombo();
  }
  tip(info.summary);
  // Only the fields this type reads (renderer/material_types.h).
  if (uses_field(m.type, kFieldColour)) {
    ImGui::ColorEdit3("Colour", &m.color.x, ImGuiColorEditFlags_Float);
    tip("Linear RGB colour (albedo, reflectance or tint, see Type).");
    texture_slot(doc, state, i, &Material::color_texture);
  }
  if (uses_field(m.type, kFieldEmission)) {
    // As in Blender: a colour (0 to 1) and a separate, unbounded strength; emission = both.
    EmissionForm form = shown_emission(state.shown_emission, i, m.emission);
    bool changed = ImGui::ColorEdit3("Emission", &form.colour.x, ImGuiColorEditFlags_Float);
    tip("Colour of the emitted light (linear RGB, 0 to 1); Strength says how bright.");
    changed |= ImGui::DragFloat("Strength", &form.strength, 0.05f, 0, FLT_MAX, "%.3f", kClamp);
    tip("Emitted radiance = colour x strength: 0 emits no light; there is no upper limit.");
    if (changed) m.emission = set_emission(state.shown_emission, i, form);
    texture_slot(doc, state, i, &Material::emission_texture);
  }
  if (uses_field(m.type, kFieldRoughness)) {
    ImGui::DragFloat("Roughness", &m.roughness, 0.005f, 0, 1, "%.3f", kClamp);
    tip("Microfacet roughness (GGX alpha = roughness^2): 0 is perfectly smooth.");
    texture_slot(doc, state, i, &Material::roughness_texture);
  }
  if (uses_field(m.type, kFieldIor)) {
    ImGui::DragFloat("IOR", &m.ior, 0.005f, 0.1f, 4.0f, "%.3f", kClamp);
    tip("Index of refraction: sets the Fresnel reflectance (1.5 is glass).");
  }
  if (uses_field(m.type, kFieldOpacity)) {
    ImGui::DragFloat("Opacity", &m.opacity, 0.005f, 0, 1, "%.3f", kClamp);
    tip("Coverage: below 1, rays pass through the surface with that probability (cut-outs).");
  }
  int users = 0;
  for (const Sphere& s : doc.scene.spheres) users += s.material == m.name;
  for (const Quad& q : doc.scene.quads) users += q.material == m.name;
  ImGui::TextDisabled("used by %d object(s)", users);
  // Assign to the previously selected object is awkward without it: offer the objects here.
  const bool assign = ImGui::BeginCombo("Assign to", "choose an object");
  tip("Give this material to an object.");
  if (assign) {
    for (Sphere& s : doc.scene.spheres)
      if (ImGui::Selectable(("sphere " + s.name).c_str(), s.material == m.name)) s.material = m.name;
    for (Quad& q : doc.scene.quads)
      if (ImGui::Selectable(("quad " + q.name).c_str(), q.material == m.name)) q.material = m.name;
    ImGui::EndCombo();
  }
}

void texture_properties(Document& doc, EditorState& state, int i) {
  Texture& t = doc.scene.textures[i];
  name_field(doc, state, doc.selection);
  ImGui::TextWrapped("File: %s", t.path.c_str());
  unsigned thumb = state.thumbnails.get(resolve_asset_path(doc.scene, t.path), 160);
  if (thumb) ImGui::Image(tex_id(thumb), ImVec2(ui_units(160), ui_units(160)));
  else ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "cannot read the image");
}

void environment_properties(Document& doc, EditorState& state) {
  Environment& e = doc.scene.environment;
  bool textured = !e.texture.empty();
  if (textured) {
    ImGui::TextWrapped("HDR map: %s", e.texture.c_str());
    if (ImGui::SmallButton("Use a colour instead")) e.texture.clear();
    tip("Drop the map and light the scene with a uniform colour.");
    ImGui::SameLine();
  } else {
    ImGui::ColorEdit3("Colour", &e.color.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
    tip("Radiance of a uniform sky (linear RGB).");
  }
  if (ImGui::SmallButton(textured ? "Other HDR file..." : "HDR file...")) choose_file(doc, state, FilePurpose::environment);
  tip("An equirectangular .hdr or .exr map (or drop one on the window).");
  ImGui::DragFloat("Intensity", &e.intensity, 0.01f, 0, 1e4f, "%.3f", kClamp);
  tip("Multiplies the environment's radiance.");
  ImGui::DragFloat("Rotation", &e.rotation_deg, 0.5f, -360, 360, "%.1f deg", kClamp);
  tip("Turns the map about the vertical axis.");
}

// The estimator: not part of the scene, so no undo step and no save; a change restarts the
// accumulation through the renderer's sync.
void sampling_properties(EditorState& state) {
  RenderOptions& o = state.viewport.estimator;
  section_title("Sampling");
  ImGui::Checkbox("Light sampling", &o.light_sampling);
  tip("Next-event estimation: sample emitters directly (less noise, same answer).");
  ImGui::Checkbox("Environment sampling", &o.environment_sampling);
  tip("Sample the environment map by its brightness (less noise, same answer).");
  ImGui::Checkbox("Russian roulette", &o.russian_roulette);
  tip("End dim paths at random, unbiased: faster samples, a little more noise each.");
  bool sobol = o.sampler == SamplerKind::sobol;
  if (ImGui::Checkbox("Sobol sampler", &sobol)) o.sampler = sobol ? SamplerKind::sobol : SamplerKind::pcg;
  tip("Quasi-random (Owen-scrambled Sobol) samples instead of independent ones.");
  bool clamp = o.clamp > 0;
  if (ImGui::Checkbox("Clamp fireflies (biased)", &clamp)) o.clamp = clamp ? 10.0f : 0.0f;
  tip("Caps each path's luminance: fewer bright specks, but a darker, wrong image.");
  if (clamp) ImGui::DragFloat("Clamp luminance", &o.clamp, 0.1f, 0.01f, 1e6f, "%.2f", kClamp);
  if (clamp) tip("The largest luminance one path may add.");
  ImGui::Checkbox("Adaptive sampling", &o.adaptive);
  tip("After 16 samples, pixels whose estimated error is already low skip passes (every 8th\npass samples all), so samples go where the noise is.");
  // The viewport pauses at this estimated relMSE; 0: never.
  float target = static_cast<float>(state.viewport.target_error);
  if (ImGui::InputFloat("Target error", &target, 0, 0, "%.2e") && target >= 0)
    state.viewport.target_error = target;
  tip("Pause the viewport once the estimated relMSE is at most this (0: never).");
  if (clamp) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("Clamping darkens bright highlights: the image no longer converges to the right answer.");
    ImGui::PopStyleColor();
  }
}

void camera_properties(Document& doc) {
  Camera& c = doc.scene.camera;
  ImGui::DragFloat3("Position", &c.position.x, 0.01f);
  tip("Where the camera is (world units).");
  ImGui::DragFloat3("Target", &c.target.x, 0.01f);
  tip("The point it looks at (orbit turns around it).");
  ImGui::DragFloat("Field of view", &c.vfov_deg, 0.2f, 1, 150, "%.1f deg", kClamp);
  tip("Vertical field of view of the film (the frame in the viewport).");
  ImGui::DragFloat("Aperture", &c.aperture_radius, 0.001f, 0, 10, "%.4f", kClamp);
  tip("Lens radius: 0 is a pinhole (all sharp); larger blurs what is off the focus distance.");
  ImGui::DragFloat("Focus distance", &c.focus_distance, 0.01f, 1e-3f, 1e6f, "%.3f", kClamp);
  tip("Distance along the view that is sharp (Ctrl+click in the viewport sets it).");
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("Ctrl+click in the viewport focuses there");
  ImGui::PopStyleColor();
  section_title("Render");
  ImGui::DragInt("Max bounces", &doc.scene.render.max_bounces, 0.1f, 0, 64, "%d", kClamp);
  tip("Longest path, in scattering events (0: emitters and the sky only).");
  int seed = static_cast<int>(doc.scene.render.seed);
  if (ImGui::InputInt("Seed", &seed) && seed >= 0) doc.scene.render.seed = static_cast<uint32_t>(seed);
  tip("Random seed: another seed gives other noise, the same expected image.");
  int film[2] = {doc.scene.film.width, doc.scene.film.height};
  if (ImGui::InputInt2("Film size", film) && film[0] > 0 && film[1] > 0)
    doc.scene.film = {film[0], film[1]};
  tip("The size Export writes; the viewport shows this frame (the rest dimmed).");
}

}  // namespace

void draw_properties(Document& doc, EditorState& state) {
  Selection sel = doc.selection;
  Scene& s = doc.scene;
  ImGui::PushItemWidth(-ui_units(110));
  auto valid = [](int i, size_t n) { return i >= 0 && i < static_cast<int>(n); };
  if (sel.kind == SelectionKind::sphere && valid(sel.index, s.spheres.size())) {
    section_title("Sphere");
    sphere_properties(doc, state, sel.index);
  } else if (sel.kind == SelectionKind::quad && valid(sel.index, s.quads.size())) {
    section_title("Quad");
    quad_properties(doc, state, sel.index);
  } else if (sel.kind == SelectionKind::material && valid(sel.index, s.materials.size())) {
    section_title("Material");
    material_properties(doc, state, sel.index);
  } else if (sel.kind == SelectionKind::texture && valid(sel.index, s.textures.size())) {
    section_title("Texture");
    texture_properties(doc, state, sel.index);
  } else if (sel.kind == SelectionKind::environment) {
    section_title("Environment");
    environment_properties(doc, state);
  } else {
    section_title("Camera");
    camera_properties(doc);
    draw_camera_views(doc, state);
    sampling_properties(state);
  }
  // The selected object's material right below it: the common edit needs no second click.
  std::string* material = nullptr;
  if (sel.kind == SelectionKind::sphere && valid(sel.index, s.spheres.size())) material = &s.spheres[sel.index].material;
  if (sel.kind == SelectionKind::quad && valid(sel.index, s.quads.size())) material = &s.quads[sel.index].material;
  if (material) {
    int m = find_material(s, *material);
    if (m >= 0 && ImGui::CollapsingHeader(("Material: " + *material).c_str())) {
      ImGui::PushID("inline material");
      Selection saved = doc.selection;
      doc.selection = {SelectionKind::material, m};  // name_field renames what is selected
      material_properties(doc, state, m);
      if (doc.selection == Selection{SelectionKind::material, m}) doc.selection = saved;
      ImGui::PopID();
    }
  }

  section_title("Display");
  // Exposure and tonemap only re-run the tonemap pass (the renderer's display digest).
  // A drag field, not a slider: a slider's grab sits on its value text (at 0 stops, in the
  // middle of "0.00 stops").
  ImGui::DragFloat("Exposure", &s.display.exposure, 0.02f, -10, 10, "%+.2f stops", kClamp);
  tip("Brightness in stops, -10 to +10: drag sideways, or click to type\n"
      "(re-runs only the tonemap: the samples are kept).");
  int tonemap = static_cast<int>(s.display.tonemap);
  static const char* const kTonemaps[] = {"filmic", "linear"};
  if (ImGui::Combo("Tonemap", &tonemap, kTonemaps, 2)) s.display.tonemap = static_cast<Tonemap>(tonemap);
  tip("Filmic rolls highlights off; linear clips at 1 (the samples are kept).");
  int res = static_cast<int>(state.viewport.resolution);
  static const char* const kResolutions[] = {"auto (fluid UI)", "full", "1/2", "1/4"};
  if (ImGui::Combo("Preview", &res, kResolutions, 4)) {
    state.viewport.resolution = static_cast<ViewportResolution>(res);
    state.settings.preview = state.viewport.resolution;
    settings_changed(state);
  }
  tip("Viewport resolution. auto: coarse while you edit (fluid UI), refining to full\n"
      "resolution when idle. Remembered between sessions.");
  ImGui::Checkbox("Denoise preview (biased)", &state.viewport.denoise);
  tip("Show the image denoised by Open Image Denoise every few frames (biased: blurs detail).");
  ImGui::PopItemWidth();
}

}  // namespace glint
