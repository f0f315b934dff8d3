#include "loop/uv_error.h"

#include <uv.h>

namespace radfarm::loop {

std::string UvErrorText(std::string_view what, int code) {
  std::string text(what);
  text += ": ";
  text += uv_strerror(code);
  text += " (";
  text += uv_err_name(code);
  text += ")";
  return text;
}

}  // namespace radfarm::loop
