// Appends with one atomic per subgroup instead of one per invocation: the active invocations that
// `want` a slot get consecutive indices from `counter` (which must be a buffer member lvalue).
// Contended atomics on one address are what the SVO build's passes cost most on lavapipe.
#ifndef DYNGI_SUBGROUP_APPEND_GLSL
#define DYNGI_SUBGROUP_APPEND_GLSL
#extension GL_KHR_shader_subgroup_ballot : require
#define DYNGI_SUBGROUP_APPEND(counter, want, index)                  \
  {                                                                  \
    uvec4 ballot_ = subgroupBallot(want);                            \
    uint count_ = subgroupBallotBitCount(ballot_);                   \
    uint base_ = 0u;                                                 \
    if (count_ > 0u && subgroupElect()) base_ = atomicAdd(counter, count_); \
    base_ = subgroupBroadcastFirst(base_);                           \
    index = base_ + subgroupBallotExclusiveBitCount(ballot_);        \
  }
#endif
