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

/// Minimal Markdown to HTML for the report: # headings, pipe tables, images, paragraphs.
/// Images `![alt](path)` are embedded from base_dir/path as data URIs.
std::string MarkdownToHtml(const std::string& markdown, const std::string& base_dir);

std::string Base64(const std::string& bytes);

}  // namespace slambox::render

namespace slambox {
// The app calls the entry points by their short names.
using render::WriteReport;
}  // namespace slambox
