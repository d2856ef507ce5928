// isa_target.hpp — switches on one copy's instruction set. Included last,
// after every other header, by the files compiled once per instruction set
// (fast_path.cpp, instanced_packets.cpp; tools/render/CMakeLists.txt):
// plain x86-64, AVX2 + FMA, and AVX-512, each copy in its own namespace
// (RT_FAST_ISA). fast_path_dispatch.cpp picks one at start-up from what the
// CPU has.
//
// Why a pragma here rather than -mavx2 on the command line: the headers'
// inline functions (std::vector, glm, ...) are then compiled for plain
// x86-64 in every copy, so whichever copy the linker keeps is safe on any
// CPU; only the including file's own code (in an anonymous namespace,
// private to each copy) uses the wide units. So no header may follow this
// one.
// Contraction is off for the whole project and FMA appears only where the
// code writes std::fma (exactly rounded on every path, in hardware or not),
// so all copies give the same bits.
#ifndef RT_FAST_ISA
#define RT_FAST_ISA isa_baseline
#endif
#if defined(RT_FAST_AVX512)
#pragma GCC target("avx512f,avx512vl,avx512bw,avx512dq,avx2,fma,bmi,bmi2,lzcnt,popcnt")
#elif defined(RT_FAST_AVX2)
#pragma GCC target("avx2,fma,bmi,bmi2,lzcnt,popcnt")
#endif
