#include "union/crossing_doubles.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace mr::surface_union {

namespace {

using u128 = unsigned __int128;
using i128 = __int128;

/// Two's complement integer of L 64-bit limbs. The sums of products below stay under
/// 2^(64 L - 1) in magnitude for the inputs each size is used for, so arithmetic modulo
/// 2^(64 L) is exact.
template <int L>
struct Int {
  uint64_t l[L];  // least significant first

  static Int of(i128 v) {
    Int r;
    r.l[0] = uint64_t(v);
    r.l[1] = uint64_t(u128(v) >> 64);
    for (int k = 2; k < L; ++k) r.l[k] = v < 0 ? ~uint64_t(0) : 0;
    return r;
  }
  bool negative() const { return l[L - 1] >> 63; }
  Int operator-() const {
    Int r;
    uint64_t carry = 1;
    for (int k = 0; k < L; ++k) {
      const u128 s = u128(~l[k]) + carry;
      r.l[k] = uint64_t(s);
      carry = uint64_t(s >> 64);
    }
    return r;
  }
  friend Int operator+(const Int& a, const Int& b) {
    Int r;
    uint64_t carry = 0;
    for (int k = 0; k < L; ++k) {
      const u128 s = u128(a.l[k]) + b.l[k] + carry;
      r.l[k] = uint64_t(s);
      carry = uint64_t(s >> 64);
    }
    return r;
  }
  friend Int operator-(const Int& a, const Int& b) { return a + -b; }
  /// a m modulo 2^(64 L).
  friend Int operator*(const Int& a, i128 m) {
    const u128 mag = m < 0 ? u128(0) - u128(m) : u128(m);
    const uint64_t lo = uint64_t(mag), hi = uint64_t(mag >> 64);
    Int r;
    uint64_t carry = 0;
    for (int k = 0; k < L; ++k) {
      const u128 p = u128(a.l[k]) * lo + carry;
      r.l[k] = uint64_t(p);
      carry = uint64_t(p >> 64);
    }
    if (hi) {
      carry = 0;
      for (int k = 1; k < L; ++k) {
        const u128 p = u128(a.l[k - 1]) * hi + r.l[k] + carry;
        r.l[k] = uint64_t(p);
        carry = uint64_t(p >> 64);
      }
    }
    return m < 0 ? -r : r;
  }
  Int magnitude() const { return negative() ? -*this : *this; }
  bool is_zero() const {
    uint64_t any = 0;
    for (int k = 0; k < L; ++k) any |= l[k];
    return any == 0;
  }
  int bit_length() const {  // of a nonnegative value
    for (int k = L - 1; k >= 0; --k)
      if (l[k]) return 64 * k + 64 - __builtin_clzll(l[k]);
    return 0;
  }
  /// Bits [low, low + 128) of a nonnegative value (bits below 0 read as zero).
  u128 bits_from(int low) const {
    u128 r = 0;
    for (int k = 0; k < L; ++k) {
      const int at = 64 * k - low;  // where the limb's bit 0 lands
      if (at >= 128 || at <= -64) continue;
      r |= at >= 0 ? u128(l[k]) << at : u128(l[k] >> -at);
    }
    return r;
  }
};

/// The values as integers z times 2^e, the rationals' scaling (each nonzero double is
/// m 2^(ilogb - 52) with |m| < 2^53), read from the bits; returns how many binades the
/// exponents span (-1 for a subnormal). Fills z only when they span at most `widest`.
int scale_to_stack_integers(const double* v, int n, int widest, i128* z, int& e) {
  int exponent[15];
  int64_t mantissa[15];
  int emin = INT_MAX, emax = INT_MIN;
  for (int i = 0; i < n; ++i) {
    uint64_t bits;
    std::memcpy(&bits, &v[i], sizeof bits);
    const int biased = int(bits >> 52) & 0x7ff;
    const uint64_t fraction = bits & ((uint64_t(1) << 52) - 1);
    if (biased == 0) {
      if (fraction != 0) return -1;  // subnormal
      mantissa[i] = 0;
      continue;
    }
    const int64_t m = int64_t(fraction | uint64_t(1) << 52);
    mantissa[i] = bits >> 63 ? -m : m;
    exponent[i] = biased - 1075;  // ilogb - 52
    emin = std::min(emin, exponent[i]);
    emax = std::max(emax, exponent[i]);
  }
  if (emin == INT_MAX) emin = emax = 0;
  if (emax - emin > widest) return emax - emin;
  for (int i = 0; i < n; ++i) z[i] = mantissa[i] == 0 ? 0 : i128(mantissa[i]) * (i128(1) << (exponent[i] - emin));
  e = emin;
  return emax - emin;
}

/// A positive denominator's leading 64 bits and bit length.
struct Denominator {
  uint64_t top;
  int length;
  bool negative;
};
template <int L>
Denominator denominator(const Int<L>& den) {
  const Int<L> d = den.magnitude();
  const int bd = d.bit_length();
  return {uint64_t(d.bits_from(bd - 64)), bd, den.negative()};
}

/// num 2^e / den truncated towards zero, where the leading bits decide it.
template <int L>
bool truncated_quotient(const Int<L>& num, const Denominator& den, int e, double& out) {
  if (den.top == 0) return false;  // a and b not strictly apart: left to the rationals' checks
  if (num.is_zero()) {
    out = 0;
    return true;
  }
  const Int<L> n = num.magnitude();
  // The leading 128 bits of n over the leading 64 of den: q0 has 64 or 65 bits and lies
  // within (-4, +2) of the exact quotient scaled alike (the bits each part drops move
  // it by less). Far enough from a 53-bit boundary, it has the same leading 53 bits.
  const int bn = n.bit_length();
  const u128 q0 = n.bits_from(bn - 128) / den.top;
  const int drop = (q0 >> 64 ? 65 : 64) - 53;
  const uint64_t low = uint64_t(q0) & ((uint64_t(1) << drop) - 1);
  if (low < 4 || low > (uint64_t(1) << drop) - 3) return false;
  const int exponent = drop + (bn - 128) - (den.length - 64) + e;
  if (exponent + 52 < -1022 || exponent + 53 > 1024) return false;  // not a normal double
  const double magnitude = std::ldexp(double(uint64_t(q0 >> drop)), exponent);
  out = num.negative() != den.negative ? -magnitude : magnitude;
  return true;
}

/// Coordinate k of the crossing where it is an input double: a and b share it, the
/// plane (kEdgePlane) or the line (kSegmentLine, in the projection) is across axis k.
const double* exact_coordinate(const QPoint::Recipe& r, int k) {
  const double* v = r.v;
  if (v[k] == v[3 + k]) return &v[k];
  if (r.kind == QPoint::Recipe::kEdgePlane) return v[6 + k] == v[9 + k] && v[6 + k] == v[12 + k] ? &v[6 + k] : nullptr;
  if (k == r.i) return v[6] == v[8] ? &v[6] : nullptr;  // the line's c0_i, c1_i
  if (k == r.j) return v[7] == v[9] ? &v[7] : nullptr;
  return nullptr;
}

/// The crossing from integers under 2^(53 + span) in magnitude, with L limbs enough for
/// the quotient's parts (under 2^(4 (53 + span) + 7)). Products of two inputs are taken
/// in 128 bits while they fit (span 9 at most).
template <int L, bool kNarrow>
bool crossing_doubles(const QPoint::Recipe& recipe, const i128* z, int e, std::array<double, 3>& d) {
  auto product = [](i128 a, i128 b) {
    if constexpr (kNarrow) return Int<L>::of(a * b);
    else return Int<L>::of(a) * b;
  };
  Int<L> oa, ob;
  if (recipe.kind == QPoint::Recipe::kEdgePlane) {
    const i128 *A = z, *B = z + 3, *F0 = z + 6, *F1 = z + 9, *F2 = z + 12;
    i128 u[3], w[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = F1[k] - F0[k];
      w[k] = F2[k] - F0[k];
    }
    oa = ob = Int<L>::of(0);
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const Int<L> n = product(u[i], w[j]) - product(u[j], w[i]);
      oa = oa + n * (A[k] - F0[k]);
      ob = ob + n * (B[k] - F0[k]);
    }
  } else {
    const i128 *A = z, *B = z + 3;
    const int i = recipe.i, j = recipe.j;
    const i128 ux = z[8] - z[6], uy = z[9] - z[7];
    oa = product(ux, A[j] - z[7]) - product(uy, A[i] - z[6]);
    ob = product(ux, B[j] - z[7]) - product(uy, B[i] - z[6]);
  }
  // The point (oa B - ob A) / (oa - ob) 2^e, as its rationals; a coordinate that is a
  // double of the input (below) is its own truncation, where the quotient's leading bits
  // could not decide it.
  const Denominator den = denominator(oa - ob);
  for (int k = 0; k < 3; ++k) {
    const double* known = exact_coordinate(recipe, k);
    if (known) d[size_t(k)] = *known == 0 ? 0.0 : *known;  // rationals have no -0
    else if (!truncated_quotient(oa * z[3 + k] - ob * z[k], den, e, d[size_t(k)])) return false;
  }
  return true;
}

}  // namespace

bool truncated_crossing_on_stack(const QPoint::Recipe& recipe, std::array<double, 3>& d) {
  i128 z[15];
  int e = 0;
  const int n = recipe.kind == QPoint::Recipe::kEdgePlane ? 15 : 10;
  // Inputs under 2^62 (span 9): differences under 2^63, the parts under 2^255. Under
  // 2^126 (span 73): differences under 2^127, the parts under 2^511.
  const int span = scale_to_stack_integers(recipe.v, n, 73, z, e);
  if (span < 0 || span > 73) return false;
  if (span <= 9) return crossing_doubles<4, true>(recipe, z, e, d);
  return crossing_doubles<8, false>(recipe, z, e, d);
}

}  // namespace mr::surface_union
