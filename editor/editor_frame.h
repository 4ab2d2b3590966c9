// One frame of the editor, top to bottom (docs/DESIGN.md §2.1). Between ImGui::NewFrame() and
// the backend's draw; the app (editor_app.cpp) and the UI tests run the same function.
#pragma once

namespace glint {

class Document;
struct EditorState;
class ViewportRenderer;

// 1. input and widgets edit the document (draw_editor_ui: no rendering in there);
// 2. the viewport renders the edited scene at the panel's size of this frame;
// 3. a running export traces its slice (the viewport traced nothing meanwhile), timed as the
//    frame's tracing for the frame budget;
// 4. undo is derived (Document::end_frame), a drag in progress being one step;
// 5. the viewport image goes under the panels and ImGui::Render() builds the draw data.
void editor_frame(Document& doc, EditorState& state, ViewportRenderer& viewport);

// A frame before the viewport renderer exists (its trace programs compile for seconds on a slow
// device): the panels, and the viewport saying kCompilingShaders (ui.h) instead of an image.
void editor_frame_before_viewport(Document& doc, EditorState& state);

}  // namespace glint
