// The index.html of a comparison report (compare_report.h describes the page). Static HTML with one
// inline script; the images are the PNGs next to it, the pixel values (when small enough) and the
// report JSON are embedded, so the page works from file:// with no server.
// Does not implement: writing files (compare_report.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "verify/image_compare.h"

namespace tessera::verify {

// Largest image (bytes of its stored pixels) whose values are embedded for the pixel inspector.
constexpr size_t kMaxEmbeddedImageBytes = size_t(16) << 20;

std::string renderReportHtml(const CompareResult& result, const nlohmann::json& report);

}  // namespace tessera::verify
