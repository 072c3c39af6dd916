#pragma once
// Whether this process may run the threads a piece of work asks for. TBB and Embree start
// their workers deep inside a build, where a failure to start one (a limit of processes,
// ulimit -u, a container's pids limit, no memory for a stack) surfaces as an unknown Embree
// error or an exception thrown while another unwinds. So the threads are tried first, all
// at once, and a shortfall is said plainly, with what to do, before any work.

namespace rtiow {

// Throws std::runtime_error "cannot start N threads: <why>; ..." unless `threads` threads
// (this one included) can run at once. Checked once for the largest count asked.
void require_threads(int threads);

// Whether one more thread can start now (tried, and joined at once).
bool a_thread_can_start();

}  // namespace rtiow
