#pragma once
// `slambox report DIR`: report.md and a self-contained report.html (figures embedded as
// base64 PNG) with the tables and figures of a run or a sweep folder.
#include <string>
#include <vector>

namespace slambox::render {

enum class FolderKind { kRun, kSweep };
/// A run folder has metrics.json, a sweep folder sweep.json; otherwise InputError.
FolderKind DetectFolder(const std::string& dir);

/// Writes dir/report.md and dir/report.html from what the folder holds (figures are
/// taken from dir/figures/*.png as they are; render them first).
void WriteReport(const std::string& dir);

/// Minimal Markdown to HTML for the report: # headings (with HeadingId ids), pipe tables,
/// "- " lists, images, paragraphs with **bold**, `code` and [text](#id) links, and our own
/// <details> lines passed as they are. Images `![caption](path)` are embedded from
/// base_dir/path as data URIs, consecutive ones side by side, the caption under each.
std::string MarkdownToHtml(const std::string& markdown, const std::string& base_dir);

/// The id of a heading: lower-case letters and digits, other runs of characters as '-'
/// ("Across scenarios" -> "across-scenarios").
std::string HeadingId(const std::string& heading);

std::string Base64(const std::string& bytes);

}  // namespace slambox::render

namespace slambox {
// The app calls the entry points by their short names.
using render::WriteReport;
}  // namespace slambox
