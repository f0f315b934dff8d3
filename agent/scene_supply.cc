#include "agent/scene_supply.h"

#include <chrono>
#include <cmath>

#include "base/result.h"
#include "loop/log.h"

namespace radfarm::agent {
namespace {

using loop::LogLevel;
using loop::LogLine;

std::string NameOf(const protocol::SceneHash& hash, SceneSupply::Blob what) {
  return (what == SceneSupply::Blob::kScene ? "scene " : "point context ") +
         protocol::HashToHex(hash);
}

long Ms(double seconds) { return std::lround(seconds * 1000); }

}  // namespace

SceneSupply::SceneSupply(loop::WorkQueue& io, std::optional<SceneStore> store, std::string master,
                         Callbacks callbacks)
    : io_(io),
      store_(std::move(store)),
      master_(std::move(master)),
      callbacks_(std::move(callbacks)) {}

std::shared_ptr<const PreparedScene> SceneSupply::Find(const protocol::SceneHash& hash) {
  return recent_.Find(hash);
}

std::shared_ptr<const PreparedContext> SceneSupply::FindContext(const protocol::SceneHash& hash) {
  return recent_contexts_.Find(hash);
}

std::string SceneSupply::Name(const protocol::SceneHash& hash) const {
  auto found = pending_.find(hash);
  return NameOf(hash, found == pending_.end() ? Blob::kScene : found->second.what);
}

Status SceneSupply::Want(const protocol::SceneHash& hash, Blob what) {
  if (pending_.contains(hash)) return Ok{};
  if (undecodable_.contains(hash)) {
    return Error{NameOf(hash, what) + " could not be decoded before; it is not fetched again"};
  }
  Pending& pending = pending_[hash];
  pending.what = what;
  // Contexts are not saved: a display's are fetched once per job and replaced by its next one.
  Status started = store_ && what == Blob::kScene ? LoadFromDisk(hash) : StartFetch(hash, pending);
  if (!started) pending_.erase(hash);
  return started;
}

Status SceneSupply::LoadFromDisk(const protocol::SceneHash& hash) {
  const SceneStore* store = &*store_;
  Status submitted = io_.Submit(
      [store, hash]() -> Prepared {
        SceneStore::Loaded loaded = store->Load(hash);
        Prepared prepared;
        prepared.detail = loaded.detail;
        if (loaded.outcome != SceneStore::LoadOutcome::kFound) return prepared;
        Result<std::shared_ptr<const PreparedScene>> scene =
            PrepareScene(hash, std::move(loaded.blob),
                         [&](std::span<const uint8_t>) { return store->PathFor(hash); });
        if (!scene) {
          prepared.kind = Prepared::Kind::kUndecodable;
          prepared.detail = scene.error();
          return prepared;
        }
        prepared.kind = Prepared::Kind::kReady;
        prepared.scene = std::move(scene).value();
        prepared.detail = "loaded from " + store->PathFor(hash);
        return prepared;
      },
      [this, hash](Result<Prepared> prepared) {
        --busy_;
        OnPrepared(hash, std::move(prepared));
      });
  if (submitted) ++busy_;
  return submitted;
}

Status SceneSupply::StartFetch(const protocol::SceneHash& hash, Pending& pending) {
  pending.stage = Stage::kFetching;
  pending.assembler = std::make_unique<protocol::SceneAssembler>(hash);
  pending.requests_in_flight = 0;
  pending.chunks = 0;
  LogLine(LogLevel::kInfo, "agent") << Name(hash) << ": fetching it from " << master_;
  return RequestMore(pending);
}

Status SceneSupply::RequestMore(Pending& pending) {
  while (pending.requests_in_flight < kRequestWindow) {
    std::optional<protocol::SceneRequestMsg> request = pending.assembler->NextRequest();
    if (!request) break;
    RADFARM_RETURN_IF_ERROR(callbacks_.send_request(*request));
    ++pending.requests_in_flight;
  }
  return Ok{};
}

void SceneSupply::OnChunk(const protocol::SceneChunkMsg& chunk) {
  const protocol::SceneHash& hash = chunk.scene_hash;
  if (auto stale = stale_answers_.find(hash); stale != stale_answers_.end()) {
    if (--stale->second == 0) stale_answers_.erase(stale);
    return;
  }
  auto found = pending_.find(hash);
  if (found == pending_.end() || found->second.stage != Stage::kFetching ||
      found->second.requests_in_flight == 0) {
    LogLine(LogLevel::kWarning, "agent")
        << Name(hash) << ": ignored a chunk from " << master_ << " that was not asked for";
    return;
  }
  Pending& pending = found->second;
  --pending.requests_in_flight;
  ++pending.chunks;
  if (Status added = pending.assembler->Add(chunk); !added) {
    Abandon(hash, pending.requests_in_flight);
    Fail(hash, protocol::LeaseReturnReason::kFailed,
         "fetch from " + master_ + " failed: " + added.error());
    return;
  }
  if (pending.assembler->complete()) {
    protocol::ReceivedScene received = pending.assembler->TakeReceived();
    LogLine(LogLevel::kInfo, "agent")
        << Name(hash) << ": fetched " << received.compressed.size() << " bytes in "
        << pending.chunks << " chunks from " << master_;
    pending.assembler.reset();
    PrepareFetched(hash, std::move(received));
    return;
  }
  if (Status more = RequestMore(pending); !more) {
    Abandon(hash, pending.requests_in_flight);
    Fail(hash, protocol::LeaseReturnReason::kFailed, "fetch failed: " + more.error());
  }
}

void SceneSupply::OnUnavailable(const protocol::SceneUnavailableMsg& message) {
  const protocol::SceneHash& hash = message.scene_hash;
  if (auto stale = stale_answers_.find(hash); stale != stale_answers_.end()) {
    if (--stale->second == 0) stale_answers_.erase(stale);
    return;
  }
  auto found = pending_.find(hash);
  if (found == pending_.end() || found->second.stage != Stage::kFetching) return;
  const uint32_t in_flight = found->second.requests_in_flight;
  Abandon(hash, in_flight > 0 ? in_flight - 1 : 0);
  Fail(hash, protocol::LeaseReturnReason::kSceneUnavailable, master_ + " does not have it");
}

void SceneSupply::OnDisconnected() {
  stale_answers_.clear();
  std::erase_if(pending_, [](const auto& entry) { return entry.second.stage == Stage::kFetching; });
}

void SceneSupply::Abandon(const protocol::SceneHash& hash, uint32_t answers_due) {
  if (answers_due > 0) stale_answers_[hash] += answers_due;
}

void SceneSupply::PrepareFetched(const protocol::SceneHash& hash,
                                 protocol::ReceivedScene received) {
  Pending& pending = pending_[hash];
  pending.stage = Stage::kPreparing;
  const SceneStore* store = store_ ? &*store_ : nullptr;
  Status submitted = io_.Submit(
      [store, hash, what = pending.what, received = std::move(received)]() mutable -> Prepared {
        Prepared prepared;
        // Written once decoded (an undecodable scene is not kept), before the caster is built
        // from the file; made durable and put in place only once the scene is ready (OnPrepared).
        auto save = [&](std::span<const uint8_t> decoded) -> std::string {
          if (store == nullptr) return "";
          Result<AtomicFileWriter> written = store->Write(hash, decoded);
          if (!written) {
            prepared.detail = "kept in memory only: " + written.error();
            return "";
          }
          prepared.unsaved = std::make_shared<AtomicFileWriter>(std::move(written).value());
          return prepared.unsaved->temporary_path();
        };
        const auto unpacking = std::chrono::steady_clock::now();
        // Consumes the compressed bytes: they are not held through the caster's build.
        Result<std::vector<uint8_t>> blob = protocol::UnpackReceived(std::move(received));
        prepared.times.unpack =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - unpacking).count();
        if (!blob) {
          prepared.kind = Prepared::Kind::kBadTransfer;
          prepared.detail = blob.error();
          return prepared;
        }
        if (what == Blob::kPointContext) {
          Result<std::shared_ptr<const PreparedContext>> context =
              PrepareContext(hash, std::move(blob).value());
          if (!context) {
            prepared.kind = Prepared::Kind::kUndecodable;
            prepared.detail = context.error();
            return prepared;
          }
          prepared.kind = Prepared::Kind::kReady;
          prepared.context = std::move(context).value();
          return prepared;
        }
        Result<std::shared_ptr<const PreparedScene>> scene =
            PrepareScene(hash, std::move(blob).value(), save, &prepared.times);
        if (!scene) {
          prepared.kind = Prepared::Kind::kUndecodable;
          prepared.detail = scene.error();
          return prepared;
        }
        prepared.kind = Prepared::Kind::kReady;
        prepared.scene = std::move(scene).value();
        return prepared;
      },
      [this, hash](Result<Prepared> prepared) {
        --busy_;
        OnPrepared(hash, std::move(prepared));
      });
  if (submitted) {
    ++busy_;
  } else {
    OnPrepared(hash, Error{submitted.error()});
  }
}

void SceneSupply::OnPrepared(const protocol::SceneHash& hash, Result<Prepared> prepared) {
  auto found = pending_.find(hash);
  if (found == pending_.end()) return;  // cannot happen: loads and builds are never abandoned
  if (!prepared) {
    Fail(hash, protocol::LeaseReturnReason::kFailed, prepared.error());
    return;
  }
  switch (prepared->kind) {
    case Prepared::Kind::kReady: {
      if (prepared->context) {
        LogLine(LogLevel::kInfo, "agent")
            << Name(hash) << ": ready, " << prepared->context->patch_count()
            << " patches; decompressed and its SHA-256 checked in " << Ms(prepared->times.unpack)
            << " ms";
        pending_.erase(found);
        recent_contexts_.Insert(prepared->context);
        callbacks_.on_context_ready(prepared->context);
        return;
      }
      LogLine(LogLevel::kInfo, "agent")
          << Name(hash) << ": ready, " << prepared->scene->patch_count() << " patches"
          << (prepared->detail.empty() ? "" : "; " + prepared->detail);
      const PrepareTimes& t = prepared->times;
      LogLine(LogLevel::kDebug, "agent")
          << Name(hash) << ": decompressed and its SHA-256 checked in " << Ms(t.unpack)
          << " ms, checked in " << Ms(t.check) << " ms, written in " << Ms(t.decoded_callback)
          << " ms, ray caster built in " << Ms(t.caster) << " ms, shapes decoded in "
          << Ms(t.shapes) << " ms";
      pending_.erase(found);
      recent_.Insert(prepared->scene);
      callbacks_.on_ready(prepared->scene);
      if (prepared->unsaved) Commit(hash, std::move(prepared->unsaved));
      return;
    }
    case Prepared::Kind::kNotOnDisk: {
      if (!prepared->detail.empty()) {
        LogLine(LogLevel::kWarning, "agent") << Name(hash) << ": " << prepared->detail;
      }
      if (Status fetching = StartFetch(hash, found->second); !fetching) {
        Abandon(hash, found->second.requests_in_flight);
        Fail(hash, protocol::LeaseReturnReason::kFailed, "cannot fetch it: " + fetching.error());
      }
      return;
    }
    case Prepared::Kind::kBadTransfer:
      Fail(hash, protocol::LeaseReturnReason::kFailed,
           "fetch from " + master_ + " failed: " + prepared->detail);
      return;
    case Prepared::Kind::kUndecodable:
      undecodable_.insert(hash);
      Fail(hash, protocol::LeaseReturnReason::kFailed, prepared->detail);
      return;
  }
}

void SceneSupply::Commit(const protocol::SceneHash& hash,
                         std::shared_ptr<AtomicFileWriter> unsaved) {
  Status submitted =
      io_.Submit([unsaved]() -> Status { return unsaved->Commit(); },
                 [this, hash, path = unsaved->path()](Status committed) {
                   --busy_;
                   if (committed) {
                     LogLine(LogLevel::kInfo, "agent") << Name(hash) << ": saved as " << path;
                   } else {
                     LogLine(LogLevel::kWarning, "agent")
                         << Name(hash) << ": kept in memory only: " << committed.error();
                   }
                 });
  if (submitted) ++busy_;
}

void SceneSupply::Fail(const protocol::SceneHash& hash, protocol::LeaseReturnReason reason,
                       const std::string& why) {
  const std::string name = Name(hash);
  pending_.erase(hash);
  LogLine(LogLevel::kWarning, "agent") << name << ": " << why;
  callbacks_.on_failed(hash, reason, why);
}

}  // namespace radfarm::agent
