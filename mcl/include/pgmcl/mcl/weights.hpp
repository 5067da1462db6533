#pragma once
/// Particle weights in log space: log-sum-exp normalisation and the effective sample size.
/// Per-beam log-likelihoods summed over ~1000 beams reach -1e5, where exp() underflows to
/// zero for every particle; shifting by the maximum before exponentiating keeps the ratios.

#include <span>

namespace pgmcl {

/// log(sum_i exp(v_i)), computed as m + log(sum_i exp(v_i - m)) with m = max_i v_i.
/// Empty input or all entries -inf give -inf. NaN entries count as -inf (zero weight).
/// Any +inf entry gives +inf.
[[nodiscard]] double log_sum_exp(std::span<const double> v) noexcept;

/// Normalises log weights: on return `log_w[i]` holds log(w_i) with sum_i w_i = 1 and
/// `w_out[i]` holds w_i. Returns the log normaliser log(sum_i exp(log_w[i])) of the input
/// (for the filter: the log marginal likelihood of the scan up to a constant).
///
/// Degenerate inputs never produce NaN weights:
///  - every entry -inf or NaN (no particle explains the scan): uniform weights 1/n,
///    log_w = -log(n), and the return value is -inf. `!std::isfinite(result)` is the flag.
///  - some entries +inf: those share the weight equally, the rest get 0; returns +inf.
///  - NaN entries otherwise count as -inf (zero weight).
/// Empty input returns -inf and writes nothing.
/// Throws std::invalid_argument if the spans differ in size.
double normalise_log_weights(std::span<double> log_w, std::span<double> w_out);

/// Kish's effective sample size (sum w)^2 / sum w^2, which is 1 / sum w^2 for normalised
/// weights: n for uniform weights, 1 when one particle carries everything.
/// Returns 0 for empty input or all-zero weights.
[[nodiscard]] double effective_sample_size(std::span<const double> w) noexcept;

}  // namespace pgmcl
