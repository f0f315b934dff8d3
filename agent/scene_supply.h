// SceneSupply: gets each blob a lease names by its hash ready, from the first place that has it:
// a scene ready for batches (a PreparedScene), or a display step's point context ready for point
// leases (a PreparedContext). Both travel the same way; they differ only in how they are prepared
// and that contexts are not saved.
//   1. memory: the last 2 prepared scenes and the last 2 prepared contexts (RecentPrepared);
//   2. scenes only: the state directory, if any (SceneStore): the hash is checked, a damaged file
//      is deleted;
//   3. the master: SceneRequests through a SceneAssembler, up to kRequestWindow of them in flight
//      (the master answers in order); a verified scene blob is then written to a temporary file in
//      the state directory, which is fsynced and renamed into place only after on_ready.
// Disk I/O, decompression and the hash check, decoding and the RayCaster build run on the I/O work
// queue, never on the loop thread.
//
// One blob's way (`pending_` holds it until it ends in on_ready/on_context_ready or on_failed):
//
//   Want --scene, state dir--> kLoading --file ok: decoded, caster built--> on_ready
//     |                          |
//     |                          +--no file, damaged file--+
//     +--context, or no state dir--------------------------+--> kFetching
//   kFetching --last chunk--> kPreparing
//   kFetching --SceneUnavailable, bad chunk--> on_failed
//   kPreparing --unpacked and checked, decoded, (a scene) written, caster built--> on_ready (then
//              the scene's file committed: Commit) or on_context_ready;
//              --bytes not the blob asked for, cannot decode--> on_failed
//
// A blob that cannot be decoded is remembered (same hash, same bytes) and refused at once later.
// A fetch belongs to its connection: OnDisconnected abandons it; loads and builds run on.
//
// Loop thread only. on_ready, on_context_ready and on_failed never run inside Want().
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "agent/prepared_context.h"
#include "agent/prepared_scene.h"
#include "agent/recent_scenes.h"
#include "agent/scene_store.h"
#include "base/result.h"
#include "loop/work_queue.h"
#include "protocol/messages.h"
#include "protocol/scene_transfer.h"

namespace radfarm::agent {

class SceneSupply {
 public:
  static constexpr uint32_t kRequestWindow = 4;  // requests in flight per fetch (4 MiB)

  // What the bytes a hash names are, which says how they are prepared.
  enum class Blob { kScene, kPointContext };

  struct Callbacks {
    std::function<void(const std::shared_ptr<const PreparedScene>& scene)> on_ready;
    std::function<void(const std::shared_ptr<const PreparedContext>& context)> on_context_ready;
    std::function<void(const protocol::SceneHash& hash, protocol::LeaseReturnReason reason,
                       const std::string& why)>
        on_failed;
    // Sends a SceneRequest to the master; fails when there is no connection.
    std::function<Status(const protocol::SceneRequestMsg& request)> send_request;
  };

  // `io` must outlive this object's last delivered result (destroy the queue first). `master`
  // names the master in log lines.
  SceneSupply(loop::WorkQueue& io, std::optional<SceneStore> store, std::string master,
              Callbacks callbacks);

  // The prepared scene, or context, if it is in memory.
  std::shared_ptr<const PreparedScene> Find(const protocol::SceneHash& hash);
  std::shared_ptr<const PreparedContext> FindContext(const protocol::SceneHash& hash);
  // Starts getting `hash`, which names `what`, unless that is under way already. An error (a blob
  // known to be undecodable, or a request that cannot be sent) means no callback will follow.
  Status Want(const protocol::SceneHash& hash, Blob what = Blob::kScene);

  void OnChunk(const protocol::SceneChunkMsg& chunk);
  void OnUnavailable(const protocol::SceneUnavailableMsg& message);
  // The connection is gone, and with it the answers to every request in flight.
  void OnDisconnected();

  // Work items submitted and not yet delivered.
  size_t busy() const { return busy_; }

 private:
  enum class Stage { kLoading, kFetching, kPreparing };
  struct Pending {
    Blob what = Blob::kScene;
    Stage stage = Stage::kLoading;
    std::unique_ptr<protocol::SceneAssembler> assembler;  // kFetching
    uint32_t requests_in_flight = 0;
    uint32_t chunks = 0;
  };
  // What a work item found: a prepared scene or context, or why not.
  struct Prepared {
    // kBadTransfer: the fetched bytes did not unpack to the scene asked for (a fault of that
    // transfer, not of the scene: it may be fetched again).
    enum class Kind { kReady, kNotOnDisk, kUndecodable, kBadTransfer } kind = Kind::kNotOnDisk;
    std::shared_ptr<const PreparedScene> scene;      // kReady, a scene
    std::shared_ptr<const PreparedContext> context;  // kReady, a point context
    std::string detail;                         // a damaged file, a failed save, the decode error
    std::shared_ptr<AtomicFileWriter> unsaved;  // a fetched scene's file, to commit once ready
    PrepareTimes times;
  };

  Status LoadFromDisk(const protocol::SceneHash& hash);
  Status StartFetch(const protocol::SceneHash& hash, Pending& pending);
  Status RequestMore(Pending& pending);
  void PrepareFetched(const protocol::SceneHash& hash, protocol::ReceivedScene received);
  // "scene <hex>" or "point context <hex>", by what the pending fetch is (a scene if none).
  std::string Name(const protocol::SceneHash& hash) const;
  void OnPrepared(const protocol::SceneHash& hash, Result<Prepared> prepared);
  // Makes a fetched scene's file durable and puts it in place, on the I/O queue, after on_ready.
  void Commit(const protocol::SceneHash& hash, std::shared_ptr<AtomicFileWriter> unsaved);
  // A fetch ends before its last chunk (Fail follows): the answers still due are skipped when
  // they come.
  void Abandon(const protocol::SceneHash& hash, uint32_t answers_due);
  void Fail(const protocol::SceneHash& hash, protocol::LeaseReturnReason reason,
            const std::string& why);

  loop::WorkQueue& io_;
  std::optional<SceneStore> store_;
  std::string master_;
  Callbacks callbacks_;
  RecentScenes recent_;
  RecentContexts recent_contexts_;
  std::map<protocol::SceneHash, Pending> pending_;
  std::map<protocol::SceneHash, uint32_t> stale_answers_;  // of abandoned fetches, by scene
  std::set<protocol::SceneHash> undecodable_;
  size_t busy_ = 0;
};

}  // namespace radfarm::agent
