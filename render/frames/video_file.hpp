// What makes a video file whole: the container ffmpeg is asked for by the file's extension, and a
// check of a finished file's structure (an MP4 without its moov box, or a Matroska file whose
// segment was never closed, does not play).
#pragma once

#include <optional>
#include <string>

namespace gf::render {

/// ffmpeg's name of the container for `path`'s extension (.mp4, .mov, .mkv; any case): "mp4",
/// "mov" or "matroska"; nullopt for any other extension.
std::optional<std::string> videoContainer(const std::string& path);

/// Why the finished video at `path` is not a complete file of `container` (as videoContainer names
/// it), or nullopt when it is: MP4 and MOV files must consist of whole top-level boxes, one of them `moov` (the index a
/// player needs, written last); Matroska files must start with an EBML header and hold a segment
/// of known size that fits the file. Reads only the boxes' and elements' headers. Any thread.
std::optional<std::string> videoFileProblem(const std::string& path, const std::string& container);

}  // namespace gf::render
