// Camera rays: pinhole or thin lens (the lens is a disk of radius `aperture` in the plane
// spanned by right/up; the plane at distance `focus` along `forward` is sharp).
#ifndef GLINT_CAMERA_GLSL
#define GLINT_CAMERA_GLSL

struct CameraFrame {
  vec3 origin;
  vec3 right;    // unit
  vec3 up;       // unit, orthogonal to right and forward
  vec3 forward;  // unit view direction
  float tan_half_vfov;
  float aspect;  // width / height
  float aperture;
  float focus;
};

// film: position on the image in [0,1]^2, (0,0) the top-left corner; lens_u in [0,1)^2.
Ray camera_ray(CameraFrame cam, vec2 film, vec2 lens_u) {
  float sx = (2.0f * film.x - 1.0f) * cam.tan_half_vfov * cam.aspect;
  float sy = (1.0f - 2.0f * film.y) * cam.tan_half_vfov;
  vec3 d = cam.forward + sx * cam.right + sy * cam.up;  // forward component exactly 1
#if !defined(GLINT_NO_THIN_LENS)  // defined: a pinhole program (lens_u is drawn but unused)
  if (cam.aperture > 0.0f) {
    vec3 focus_point = cam.origin + cam.focus * d;
    vec2 lens = cam.aperture * sample_disk(lens_u);
    vec3 o = cam.origin + lens.x * cam.right + lens.y * cam.up;
    return Ray(o, normalize(focus_point - o));
  }
#endif
  return Ray(cam.origin, normalize(d));
}

#endif
