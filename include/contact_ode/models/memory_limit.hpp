#pragma once
// What this process may hold. Here, below the integrators, because a scene is refused on it too:
// a scene builds its initial state when it is made (make_scene checks its bodies' gaps on it).

namespace contact {

// The memory this process may use [bytes]: the machine's physical memory, or less where a cgroup
// (a container) or an address-space rlimit (ulimit -v) sets less. Half of this machine's memory
// let a run past a container's limit start, and meet the OOM killer (or, under ulimit -v, a failed
// allocation inside SUNDIALS, which dereferences the NULL it gets). Read once, at the first call.
double memory_limit();
// Half of it: what one run may hold (its caller, e.g. Python's copy of the samples, needs room too).
double half_the_memory_limit();

}  // namespace contact
