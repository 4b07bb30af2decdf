// Highway compiles this file once per target (foreach_target.h re-includes it); HWY_ONCE marks the
// part compiled once: the tables and the entry point of srgb_encoder.h.
#include "render/tracer/srgb_encoder.h"

#include <bit>
#include <limits>
#include <stdexcept>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "render/tracer/srgb_encoder.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "render/tracer/image.h"

HWY_BEFORE_NAMESPACE();
namespace stirrup::render {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// SrgbTables::code, lane by lane, with the same operations: v * 4096 truncated to its bin, the bin's
// code gathered, one more where v is past the next step; NaN and v <= 0 give 0, v >= 1 gives 255.
template <class DF>
hn::Vec<hn::Rebind<uint8_t, DF>> Codes(DF df, const SrgbTables& tables, hn::Vec<DF> v) {
  const hn::RebindToSigned<DF> di;
  const auto positive = hn::Gt(v, hn::Zero(df));  // false for NaN
  const auto at_least_one = hn::Ge(v, hn::Set(df, 1.0f));
  const auto inside = hn::IfThenElseZero(hn::AndNot(at_least_one, positive), v);  // in [0, 1)
  const auto bin = hn::Min(hn::ConvertTo(di, hn::Mul(inside, hn::Set(df, float(SrgbTables::kBins)))),
                           hn::Set(di, SrgbTables::kBins - 1));
  // The bins' entries, half a vector at a time in 64-bit lanes; their low halves are the codes, their
  // high halves the next steps.
  const hn::Repartition<int64_t, DF> d64;
  const hn::Half<decltype(di)> dh;
  const auto* entries = reinterpret_cast<const int64_t*>(tables.bin_entry.data());
  const auto lo = hn::GatherIndex(d64, entries, hn::PromoteTo(d64, hn::LowerHalf(dh, bin)));
  const auto hi = hn::GatherIndex(d64, entries, hn::PromoteTo(d64, hn::UpperHalf(dh, bin)));
  const auto k = hn::ConcatEven(di, hn::BitCast(di, hi), hn::BitCast(di, lo));
  const auto next_step = hn::BitCast(df, hn::ConcatOdd(di, hn::BitCast(di, hi), hn::BitCast(di, lo)));
  auto code = hn::Add(k, hn::IfThenElseZero(hn::RebindMask(di, hn::Ge(inside, next_step)), hn::Set(di, 1)));
  code = hn::IfThenElse(hn::RebindMask(di, at_least_one), hn::Set(di, 255), code);
  code = hn::IfThenElseZero(hn::RebindMask(di, positive), code);
  return hn::DemoteTo(hn::Rebind<uint8_t, DF>(), code);
}

// The RGB codes of RGBA pixels: a vector of pixels' channels apart (alpha read, not coded), the three
// codes stored interleaved again.
void SrgbCodesRgb(const float* rgba, uint8_t* rgb, size_t pixels) {
  const SrgbTables& tables = SrgbTables::get();
  const hn::ScalableTag<float> df;
  const hn::Rebind<uint8_t, decltype(df)> d8;
  const size_t lanes = hn::Lanes(df);
  size_t i = 0;
  for (; i + lanes <= pixels; i += lanes) {
    hn::Vec<decltype(df)> r, g, b, a;
    hn::LoadInterleaved4(df, rgba + 4 * i, r, g, b, a);
    hn::StoreInterleaved3(Codes(df, tables, r), Codes(df, tables, g), Codes(df, tables, b), d8, rgb + 3 * i);
  }
  for (; i < pixels; ++i)
    for (size_t c = 0; c < 3; ++c) rgb[3 * i + c] = tables.code(rgba[4 * i + c]);
}

}  // namespace HWY_NAMESPACE
}  // namespace stirrup::render
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stirrup::render {

HWY_EXPORT(SrgbCodesRgb);

SrgbTables::SrgbTables() {
  const uint32_t one = std::bit_cast<uint32_t>(1.0f);
  for (int k = 1; k < 256; ++k) {
    uint32_t lo = 0, hi = one;  // code(lo) < k <= code(hi)
    while (hi - lo > 1) {
      const uint32_t mid = lo + (hi - lo) / 2;
      (linearToSrgb8(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
    }
    step[std::size_t(k)] = std::bit_cast<float>(hi);
  }
  step[256] = std::numeric_limits<float>::infinity();
  for (int b = 0; b < kBins; ++b) {
    const float start = float(b) / float(kBins);
    int k = 0;
    while (k < 255 && step[std::size_t(k) + 1] <= start) ++k;
    bin_code[std::size_t(b)] = k;
  }
  for (int b = 0; b < kBins; ++b) {
    const int32_t next = b + 1 < kBins ? bin_code[std::size_t(b) + 1] : 255;  // the next bin's first code
    if (next - bin_code[std::size_t(b)] > 1) throw std::logic_error("SrgbTables: a bin holds two steps");
    const uint32_t next_step = std::bit_cast<uint32_t>(step[std::size_t(bin_code[std::size_t(b)]) + 1]);
    bin_entry[std::size_t(b)] = uint64_t(next_step) << 32 | uint32_t(bin_code[std::size_t(b)]);
  }
}

const SrgbTables& SrgbTables::get() {
  static const SrgbTables tables;
  return tables;
}

void srgbCodesRgb(const float* rgba, uint8_t* rgb, std::size_t pixels) {
  HWY_DYNAMIC_DISPATCH(SrgbCodesRgb)(rgba, rgb, pixels);
}

}  // namespace stirrup::render
#endif  // HWY_ONCE
