#pragma once
// floor and ceil without the library call: std::floor is not inlined without SSE4.1, and the
// precomputes' inner loops (AO maps, cone maps, horizon sweeps) call it millions of times. The
// values of std::floor / std::ceil for every |x| below 2^62 (the cast truncates towards zero).

namespace rl {

template <class Real>
Real floor_fast(Real x) {
  const Real t = Real(static_cast<long long>(x));
  return t > x ? t - Real(1) : t;
}

template <class Real>
Real ceil_fast(Real x) {
  const Real t = Real(static_cast<long long>(x));
  return t < x ? t + Real(1) : t;
}

}  // namespace rl
