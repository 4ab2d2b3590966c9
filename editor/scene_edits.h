// Edits of a scene, as free functions on plain values (no UI). Each keeps the scene valid:
// names stay unique, references follow renames, nothing dangles after a delete.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "editor/document.h"
#include "renderer/scene.h"

namespace glint {

// A name not used by any object of the same kind: base, base_2, base_3, ...
std::string unique_sphere_name(const Scene& scene, const std::string& base);
std::string unique_quad_name(const Scene& scene, const std::string& base);
std::string unique_material_name(const Scene& scene, const std::string& base);
std::string unique_texture_name(const Scene& scene, const std::string& base);

// A neutral material: grey matte, untextured, not emitting, opaque.
bool is_neutral(const Material& material);
// The material new objects get: "default" or else the first neutral material, or a new grey
// matte "default" if none is neutral (never a textured wood floor, say).
std::string default_material(Scene& scene);
// The objects that use a material, as "sphere NAME" / "quad NAME" (for the delete prompt).
std::vector<std::string> material_users(const Scene& scene, const std::string& material);

// Adds an object in front of the camera (at the focus distance along the view, at least 1 unit
// away, sized to a tenth of that distance). Returns its index. A sphere goes to the nearest free
// place in the view plane there (touching no sphere or quad) when that point is taken; a quad
// faces the camera at the nearest right-angled orientation (its Euler angles whole quarter turns).
int add_sphere(Scene& scene);
int add_quad(Scene& scene);
int add_material(Scene& scene, MaterialType type);
// Adds a texture entry for an image file; the path is stored relative to scene.base_dir when it
// lies below it. Returns the index (an existing entry for the same path is reused).
int add_texture(Scene& scene, const std::filesystem::path& file);

// Duplicates of spheres and quads sit beside the original, to the camera's right by the object's
// width and a quarter more (a gap that grows with it). Return the new index.
int duplicate(Scene& scene, Selection what);
// Deletes; a material in use or a texture in use is replaced by the default material / no
// texture in the objects that used it (the UI asks first: material_users). Returns the
// selection afterwards: nothing, so that a second Delete never removes a neighbour.
Selection remove(Scene& scene, Selection what);
// Renames; references follow. Returns false (and changes nothing) if the name is empty or taken.
bool rename(Scene& scene, Selection what, const std::string& name);
std::string name_of(const Scene& scene, Selection what);
// The sphere named `name`, else the quad of that name; nullopt when there is neither.
std::optional<Selection> find_object(const Scene& scene, const std::string& name);

// Translation of spheres and quads (the gizmo and the numeric fields).
std::optional<glm::vec3> selection_center(const Scene& scene, Selection what);
void translate(Scene& scene, Selection what, glm::vec3 delta);

// A sphere around the selected sphere or quad (for frame(), the F key); nullopt otherwise.
struct BoundingSphere {
  glm::vec3 center{0};
  float radius = 0;
};
std::optional<BoundingSphere> selection_bounds(const Scene& scene, Selection what);

// A quad as centre, size and orientation (the UI's alternative to corners). The quad's edges
// p0->p2 and p0->p1 are its local x and y axes; size is their lengths; rotation is the
// intrinsic X-Y-Z Euler angles in degrees of the frame (x, y, x cross y).
struct QuadPlacement {
  glm::vec3 center{0};
  glm::vec2 size{1};
  glm::vec3 rotation_deg{0};
};
QuadPlacement quad_placement(const Quad& quad);  // exact for rectangles; angles in -180..180
// The rotation of quad_placement: columns the unit x edge, the y edge made orthogonal to it, and
// their cross product (the identity for a degenerate quad).
glm::mat3 quad_frame(const Quad& quad);
void set_quad_placement(Quad& quad, const QuadPlacement& placement);  // makes it a rectangle

}  // namespace glint
