#pragma once
// FIR low-pass design and decimation with MATLAB's semantics (fir1, decimate(x, r, "fir")), so that a record
// generated here is sampled exactly as a MATLAB-made benchmark record is.
//
// decimate_fir follows decimate.m's FIR branch rule by rule (1-based, nd = length(x), nfilt = order + 1):
//   - b = fir1(order, 1/r);
//   - the start is padded with itemp = 2·x(1) − x(nfilt+1:−1:2), whose filtered state starts the pass over x;
//   - the end continues that state into 2·x(nd) − x(nd−1:−1:nd−2·nfilt);
//   - nout = ceil(nd/r); the kept samples are list = round(gd + 1.25):r:nd of the filtered x (gd = order/2, the
//     group delay), then itemp(nbeg:r:nbeg+nlen·r−1) of the filtered end padding, nbeg = r − (nd − list(end)),
//     nlen = nout − length(list);
//   - r = 1 returns x unchanged.
// Continuing the filter state is filtering the concatenation [start padding, x, end padding], and nbeg continues
// list's step across the join, so the kept samples are one arithmetic progression of that filtered sequence.
#include <span>
#include <vector>

namespace dampbench {

/// MATLAB fir1(order, cutoff) low-pass: the ideal response cutoff·sinc(cutoff·(i − order/2)) under a Hamming
/// window 0.54 − 0.46·cos(2πi/order), normalised to unit gain at DC (order + 1 taps, symmetric bit for bit).
/// cutoff_nyquist is a fraction of the Nyquist frequency, in (0, 1).
std::vector<double> fir1_lowpass(int order, double cutoff_nyquist);

/// MATLAB decimate(x, factor, "fir") with a filter of the given order (rules above). The output has
/// ceil(n/factor) samples; out[j] is the filtered signal centred on x[j·factor] (for even order).
/// x needs at least 2·order + 3 samples (the end padding reaches 2·(order + 1) samples back).
std::vector<double> decimate_fir(std::span<const double> x, int factor, int order = 30);

/// decimate_fir applied for each factor in turn (the benchmark's 15 kHz → 750 Hz is {2, 2, 5}).
std::vector<double> decimate_fir_cascade(std::span<const double> x, std::span<const int> factors);

}  // namespace dampbench
