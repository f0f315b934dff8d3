// The protocol's version numbers and size limits. Every incoming frame is checked against these
// before anything uses it (docs/PROTOCOL.md, "Limits").
#pragma once

#include <cstddef>
#include <cstdint>

namespace radfarm::protocol {

// The version this build writes, and the oldest one it still accepts in a Hello. Version 2 leases
// many batches in one LeaseAssignment and answers them in one LeaseResult; version 3 sends scenes
// zstd-compressed (SceneChunk.scene_size, protocol/scene_packing.h); version 4 seals every frame
// after the handshake (frame_seal.h) and adds Close code Blocklisted; version 5 packs a
// LeaseResult's hits (core/packed_hits.h: 2-3 bytes a hit instead of 16); version 6 leases the
// display's points (PointLease, PointResult). A version-4 or 5 peer still works (a frame's own
// version says how its hits are written, and the master leases points only to agents of version
// 6), so agents and master can be upgraded one at a time. Version 7 leases the direct-light start
// by patch (PointLease start_sections, PointResult punctual), to agents of version 7 alone.
// Version 8 leases a refinement step's light scores by element (PointLease score_elements,
// PointResult scores), and its agents read a scene's sky (schema/sky.fbs in the scene blob): an
// older agent would decode such a scene without it, so both, and a sky job's start and display
// points, go to version 8 alone.
inline constexpr uint16_t kProtocolVersion = 8;
inline constexpr uint16_t kMinProtocolVersion = 4;
inline constexpr uint16_t kPackedHitsVersion = 5;
inline constexpr uint16_t kPointLeaseVersion = 6;
inline constexpr uint16_t kStartLeaseVersion = 7;
inline constexpr uint16_t kScoreLeaseVersion = 8;
inline constexpr uint16_t kSkyVersion = 8;
// A start's points per side of a patch (core/direct_light.h: at most 16).
inline constexpr uint32_t kMaxStartSections = 64;

// Frame: a 4-byte little-endian length prefix, then that many bytes of FlatBuffer.
inline constexpr size_t kLengthPrefixBytes = 4;
inline constexpr uint32_t kDefaultMaxFrameBytes = 16u << 20;
// Before the handshake a peer is a stranger: the master reads frames of at most this many bytes
// from it. A Hello is 112 bytes with a short name (at most ~180 with a 64-byte one), a Proof less;
// a Close with its longest detail about 300.
inline constexpr uint32_t kMaxHandshakeFrameBytes = 512;
// Smallest well-formed frame body: root offset, identifier, a table. Anything shorter is junk.
inline constexpr uint32_t kMinFrameBytes = 12;
// No peer may announce (Welcome) or use a frame limit below this: the largest scene chunk and a
// modest batch result must always fit.
inline constexpr uint32_t kMinPeerFrameBytes = 2u << 20;

inline constexpr size_t kNonceBytes = 32;
inline constexpr size_t kTagBytes = 32;        // HMAC-SHA-256
inline constexpr size_t kSceneHashBytes = 32;  // SHA-256
// A shared secret shorter than this is refused: HMAC-SHA-256 is only as strong as its key.
inline constexpr size_t kMinSecretBytes = 32;
inline constexpr size_t kMaxSecretBytes = 1024;

inline constexpr size_t kMaxAgentNameBytes = 64;
inline constexpr uint32_t kMaxAgentThreads = 4096;
inline constexpr size_t kMaxCloseDetailBytes = 256;
inline constexpr uint32_t kMaxSceneChunkBytes = 1u << 20;
inline constexpr uint64_t kDefaultMaxSceneBytes = uint64_t{1} << 30;
inline constexpr size_t kMaxLeaseReturnEntries = 65536;
// Batches in one LeaseAssignment, results in one LeaseResult, leases in one LeaseRevoke.
inline constexpr size_t kMaxLeaseBatches = 65536;
// Points in one PointLease (and values in its PointResult): about 0.8 MB a frame, under the
// smallest frame limit a peer may announce (kMinPeerFrameBytes).
inline constexpr size_t kMaxLeasePoints = 16384;
// Gathering rays a leased point may ask for (the display's are kPointGatherRays or fewer).
inline constexpr uint32_t kMaxPointGatherRays = 1u << 16;
inline constexpr double kMaxGridStepDegrees = 90;

}  // namespace radfarm::protocol
