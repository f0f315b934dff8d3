// The StartLightSource (core/direct_start.h) of a job this master runs: its direct-light start,
// the one a refinement restart makes included, handed to the loop thread to be leased to the
// agents (start_handoff.h), and traced on the compute thread where no agent takes it. The pieces
// the agents trace give the bits the compute thread would, so the job's result does not depend
// on who traced its start.
#pragma once

#include <memory>

#include "core/direct_start.h"
#include "daemon/jobs/start_handoff.h"
#include "mesh/light_scores.h"
#include "store/job_store.h"

namespace radfarm::daemon {

// Runs on the compute thread. Throws std::runtime_error with the handoff's error when the job was
// dropped or the master stops meanwhile (the compute work then ends with it).
StartLightSource AgentsStartSource(std::shared_ptr<StartHandoff> handoff, store::JobId job);

// The LightScoreSource of such a job: each refinement step's light scores, handed over and leased
// as a start is, to agents of protocol version 8; nullopt (scored on the compute thread's pool)
// where no agent takes them or the step scores too few elements to be worth a lease.
LightScoreSource AgentsLightScoreSource(std::shared_ptr<StartHandoff> handoff, store::JobId job);

}  // namespace radfarm::daemon
