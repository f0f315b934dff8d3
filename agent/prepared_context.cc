#include "agent/prepared_context.h"

#include <utility>

#include "codec/point_context_blob.h"

namespace radfarm::agent {

Result<std::shared_ptr<const PreparedContext>> PrepareContext(const protocol::SceneHash& hash,
                                                              std::vector<uint8_t> blob) {
  Result<codec::DecodedPointContext> decoded = codec::DecodePointContext(blob);
  if (!decoded) return Error{decoded.error()};
  blob = {};  // the decoded copy is all that is kept: not held through the caster's build
  auto prepared = std::make_shared<PreparedContext>();
  prepared->hash = hash;
  auto scene = std::make_unique<const PatchScene>(std::move(decoded->scene));
  prepared->tracer = std::make_unique<const PointTracer>(*scene, std::move(decoded->context));
  prepared->scene = std::move(scene);
  return std::shared_ptr<const PreparedContext>(std::move(prepared));
}

}  // namespace radfarm::agent
