// Box2D 2.4 times every phase of every b2World::Step into b2World::GetProfile() with
// gettimeofday: ~10 timer calls per step, 10 % of `slambox simulate loop` (perf record:
// __vdso_gettimeofday 9.6 %, b2Timer 2 %). slambox never reads the profile, so the slambox
// executable defines b2Timer itself and the dynamic linker binds libbox2d's calls to these
// definitions (an executable's symbols come first in ELF symbol lookup; the link exports
// them, CMakeLists.txt). The physics is untouched: timers only fill the profile, which
// now reads 0 ms. Only this executable: programs built on the SDK keep Box2D's timers.
#include <box2d/b2_timer.h>

b2Timer::b2Timer() : m_start_sec(0), m_start_usec(0) {}
void b2Timer::Reset() {}
float b2Timer::GetMilliseconds() const { return 0.0f; }
