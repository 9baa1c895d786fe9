#pragma once
// The rule for a file a farm task's scene references (a mesh, an environment
// image, a VDB grid): it must stay inside the task's directory, where the
// worker put the scene and its assets. An absolute path or a '..' segment
// would let a submitted scene read any file of the worker's disk (and render
// it into the frame). Checked by the server when a job is submitted and by
// the renderer of a farm task (`vesper render --scene-dir-only`); a local
// `vesper render` of one's own scene may use any path.
#include <string>
#include <string_view>

namespace vesper {

// Why `ref` could name a file outside the scene's directory ("is an absolute
// path", "has a '..' segment", "contains a NUL character"), or "" when it
// cannot. Lexical: the task directory holds no symbolic links.
std::string outside_reference_problem(std::string_view ref);

}  // namespace vesper
