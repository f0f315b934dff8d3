// The status page's files (status.html, status.js, status.css in this folder), compiled into the
// daemon at build time (cmake/EmbedText.cmake), so radfarmd serves them with no files installed.
#pragma once

#include <string_view>

namespace radfarm::web {

std::string_view StatusPageHtml();
std::string_view StatusPageJs();
std::string_view StatusPageCss();

}  // namespace radfarm::web
