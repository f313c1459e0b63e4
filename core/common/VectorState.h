#pragma once
// The state of the CPU's vector registers a thread starts from. Some libraries' AVX code returns
// with the upper halves of the vector registers in use (GUI toolkits' drawing code, on their
// first use), and every thread created afterwards inherits that state. From then on each switch
// between SSE and AVX instructions - libm's exp makes several per call - costs tens of cycles:
// exp becomes some thirty times slower until the thread clears the state.

namespace activetouch {

/// Marks the upper halves of the vector registers unused (vzeroupper) on CPUs with AVX; nothing
/// elsewhere. Cheap: call it where engine work starts on a thread.
void clearUpperVectorState();

}  // namespace activetouch
