#!/usr/bin/python3
"""Reference outputs for test_decimate.cpp and test_bandlimited.cpp, made independently of the C++ code.

decimate_matlab transcribes MATLAB's decimate.m FIR branch statement by statement (filter with carried state via
scipy.signal.lfilter, the list/nbeg/nlen index rules), with b = scipy.signal.firwin(order + 1, 1/r), which is
fir1(order, 1/r). interpft_matlab transcribes MATLAB's interpft; the spline is scipy's CubicSpline with
not-a-knot ends. Inputs come from the Lehmer generator s <- 48271*s mod (2^31 - 1), x = s/2^31 - 0.5, which
integer arithmetic makes exact in both languages.

Run with Debian's /usr/bin/python3 (numpy, scipy) and paste the printed arrays into the tests.
"""
import math

import numpy as np
import scipy.interpolate
import scipy.signal


def lehmer(n, seed):
    s, out = seed, []
    for _ in range(n):
        s = 48271 * s % 2147483647
        out.append(s / 2147483648.0 - 0.5)
    return np.array(out)


def decimate_matlab(x, r, nfilt=30):
    if r == 1:
        return x.copy()
    nd = len(x)
    nout = math.ceil(nd / r)
    b = scipy.signal.firwin(nfilt + 1, 1.0 / r)
    nfilt = nfilt + 1
    itemp = 2 * x[0] - x[nfilt:0:-1]                       # idata((nfilt+1):-1:2)
    _, zi = scipy.signal.lfilter(b, 1, itemp, zi=np.zeros(len(b) - 1))
    odata, zf = scipy.signal.lfilter(b, 1, x, zi=zi)
    itemp = 2 * x[nd - 1] - x[nd - 2::-1][:2 * nfilt]      # idata((nd-1):-1:(nd-2*nfilt))
    assert len(itemp) == 2 * nfilt
    itemp, _ = scipy.signal.lfilter(b, 1, itemp, zi=zf)
    gd = (len(b) - 1) / 2                                  # grpdelay of a symmetric FIR
    lst = list(range(round(gd + 1.25), nd + 1, r))         # 1-based list = round(gd+1.25):r:nd
    odata = odata[[i - 1 for i in lst]]
    nlen = nout - len(odata)
    nbeg = r - (nd - lst[-1])
    tail = itemp[nbeg - 1:nbeg + nlen * r - 1:r]           # itemp(nbeg:r:nbeg+nlen*r-1)
    return np.concatenate([odata, tail])


def interpft_matlab(x, ny):
    m = len(x)
    a = np.fft.fft(x)
    nyqst = math.ceil((m + 1) / 2)
    b = np.concatenate([a[:nyqst], np.zeros(ny - m), a[nyqst:]])
    if m % 2 == 0:
        b[nyqst - 1] = b[nyqst - 1] / 2
        b[nyqst - 1 + ny - m] = b[nyqst - 1]
    return np.real(np.fft.ifft(b)) * ny / m


def show(name, values):
    print(f"const std::vector<double> {name} = {{")
    for i in range(0, len(values), 3):
        print("    " + ", ".join(f"{v:.17g}" for v in values[i:i + 3]) + ",")
    print("};")


def main():
    show("kFirwin31Half", scipy.signal.firwin(31, 0.5))
    show("kFirwin31Fifth", scipy.signal.firwin(31, 0.2))
    show("kDecimate3", decimate_matlab(lehmer(70, 12345), 3))
    x = lehmer(301, 777)
    for r in (2, 2, 5):
        x = decimate_matlab(x, r)
    show("kCascade225", x)
    show("kInterpftEven", interpft_matlab(lehmer(10, 4242), 30))
    show("kInterpftOdd", interpft_matlab(lehmer(9, 4243), 18))
    samples = lehmer(8, 99)
    spline = scipy.interpolate.CubicSpline(np.arange(8.0), samples, bc_type="not-a-knot")
    show("kSpline", spline(np.arange(22) / 3.0))


if __name__ == "__main__":
    main()
