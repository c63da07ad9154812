#!/usr/bin/python3
"""Prints the reference values pinned in compare/*_test.cpp, from independent implementations.

1. Write the test pairs (8-bit PNGs, exactly the pixels the tests use; the HDR pairs as EXRs):
     TWINRENDER_WRITE_TEST_PAIRS=/tmp/pairs \
       build/compare/twinrender_compare_tests --gtest_filter='*ReferencePairs.*'
2. /usr/bin/python3 compare/testdata/reference_values.py /tmp/pairs [--flip-repo DIR]

PSNR and SSIM come from scikit-image (Debian 12: python3-skimage 0.19.3, numpy 1.24.2).
With --flip-repo (a checkout of github.com/NVlabs/flip, v1.6 at commit 1eb247c), the script
builds NVlabs' C++ flip tool and prints the mean it reports for each pair at 67 and 30 pixels
per degree (`flip -r REF.png -t TEST.png -ppd 67 -v 1`), then error-map values at a few pixels
from FLIP::evaluate() in that repository's FLIP.h (a small driver, below, that loads the PNGs
as the tool does). For the HDR pairs (hdr_flip_test.cpp) it prints the tool's HDR-FLIP mean at
67 and 30 ppd, with its own exposure range or, where that is infinite (a black median), the one
our test printed, given as -cstart/-cstop, and FLIP.h's HDR error map at a few pixels.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image
import skimage
from skimage.metrics import peak_signal_noise_ratio, structural_similarity

PAIRS = ["gradient_noise", "checker_shift", "disc_blur", "colour_shift", "dark_noise",
         "black_white"]
HDR_PAIRS = ["glow_on_black", "noisy_sky"]
# Our exposure range of the pair whose median is black (HdrReferencePairs.WriteForReferenceTools
# prints it): the tool's own is infinite there.
HDR_RANGES = {"glow_on_black": ("-2.651069", "1.796123")}
HDR_PIXELS = [("glow_on_black", 40, 35), ("glow_on_black", 21, 35), ("glow_on_black", 60, 35),
              ("glow_on_black", 30, 20), ("glow_on_black", 5, 5), ("noisy_sky", 10, 10),
              ("noisy_sky", 50, 40), ("noisy_sky", 70, 20), ("noisy_sky", 90, 60)]
# (pair, x, y) pixels whose FLIP error flip_test.cpp pins.
FLIP_PIXELS = [("checker_shift", 15, 14), ("checker_shift", 48, 35), ("checker_shift", 0, 0),
               ("disc_blur", 27, 35), ("disc_blur", 48, 13), ("colour_shift", 96, 70),
               ("gradient_noise", 84, 60), ("dark_noise", 10, 50)]

DRIVER = r"""
#include "src/cpp/FLIP.h"
#include "src/cpp/tool/imagehelpers.h"
#include <cstdio>
#include <cstdlib>
int main(int argc, char** argv) {  // REF.png TEST.png PPD X Y [X Y ...]
    FLIP::image<FLIP::color3> ref, test;
    if (!ImageHelpers::load(ref, argv[1]) || !ImageHelpers::load(test, argv[2])) return 1;
    ref.sRGBToLinearRGB();
    test.sRGBToLinearRGB();
    FLIP::Parameters params;
    params.PPD = float(std::atof(argv[3]));
    FLIP::image<float> map(ref.getWidth(), ref.getHeight());
    FLIP::evaluate(ref, test, false, params, map);
    for (int i = 4; i + 1 < argc; i += 2)
        std::printf("%.7f\n", map.get(std::atoi(argv[i]), std::atoi(argv[i + 1])));
}
"""

HDR_DRIVER = r"""
#include "src/cpp/FLIP.h"
#include "src/cpp/tool/imagehelpers.h"
#include <cstdio>
#include <cstdlib>
int main(int argc, char** argv) {  // REF.exr TEST.exr PPD CSTART CSTOP X Y [X Y ...]
    FLIP::image<FLIP::color3> ref, test;
    if (!ImageHelpers::load(ref, argv[1]) || !ImageHelpers::load(test, argv[2])) return 1;
    FLIP::Parameters params;
    params.PPD = float(std::atof(argv[3]));
    params.startExposure = float(std::atof(argv[4]));
    params.stopExposure = float(std::atof(argv[5]));
    FLIP::image<float> map(ref.getWidth(), ref.getHeight(), 0.0f);
    FLIP::evaluate(ref, test, true, params, map);
    double sum = 0.0;
    for (int y = 0; y < map.getHeight(); ++y)
        for (int x = 0; x < map.getWidth(); ++x) sum += map.get(x, y);
    std::printf("exposures %.6f to %.6f, %d; map mean %.7f\n", params.startExposure,
                params.stopExposure, params.numExposures,
                sum / (map.getWidth() * map.getHeight()));
    for (int i = 6; i + 1 < argc; i += 2)
        std::printf("(%s, %s) %.7f\n", argv[i], argv[i + 1],
                    map.get(std::atoi(argv[i]), std::atoi(argv[i + 1])));
}
"""


def load(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("pairs", help="folder with NAME.ref.png and NAME.test.png")
    parser.add_argument("--flip-repo", help="checkout of github.com/NVlabs/flip")
    args = parser.parse_args()

    print(f"scikit-image {skimage.__version__}, numpy {np.__version__}")
    print(f"{'pair':16s} {'psnr_dB':>12s} {'ssim':>12s}")
    for name in PAIRS:
        ref = load(os.path.join(args.pairs, name + ".ref.png"))
        test = load(os.path.join(args.pairs, name + ".test.png"))
        psnr = peak_signal_noise_ratio(ref, test, data_range=1.0)
        ssim = structural_similarity(ref, test, channel_axis=2, gaussian_weights=True, sigma=1.5,
                                     use_sample_covariance=False, data_range=1.0)
        print(f"{name:16s} {psnr:12.6f} {ssim:12.8f}")

    if not args.flip_repo:
        return
    with tempfile.TemporaryDirectory() as tmp:
        tool = os.path.join(tmp, "flip")
        driver = os.path.join(tmp, "driver")
        with open(driver + ".cpp", "w") as f:
            f.write(DRIVER)
        subprocess.run(["g++", "-std=c++17", "-O2", "-fopenmp", "-o", tool,
                        os.path.join(args.flip_repo, "src/cpp/tool/FLIP-tool.cpp")], check=True)
        subprocess.run(["g++", "-std=c++17", "-O2", "-fopenmp", "-I", args.flip_repo, "-o", driver,
                        driver + ".cpp"], check=True)
        print(f"\nNVlabs flip tool, mean (flip -r REF -t TEST -ppd PPD -v 1)")
        print(f"{'pair':16s} {'ppd 67':>10s} {'ppd 30':>10s}")
        for name in PAIRS:
            means = []
            for ppd in ("67", "30"):
                out = subprocess.run([tool, "-r", os.path.join(args.pairs, name + ".ref.png"),
                                      "-t", os.path.join(args.pairs, name + ".test.png"),
                                      "-ppd", ppd, "-v", "1", "--no-error-map"],
                                     check=True, capture_output=True, text=True, cwd=tmp).stdout
                means.append(out.split("Mean:")[1].split()[0])
            print(f"{name:16s} {means[0]:>10s} {means[1]:>10s}")
        print("\nFLIP.h error map at 67 ppd")
        for name, x, y in FLIP_PIXELS:
            out = subprocess.run([driver, os.path.join(args.pairs, name + ".ref.png"),
                                  os.path.join(args.pairs, name + ".test.png"), "67", str(x),
                                  str(y)], check=True, capture_output=True, text=True).stdout
            print(f"{name:16s} ({x:2d}, {y:2d}) {out.strip()}")
        if not os.path.exists(os.path.join(args.pairs, HDR_PAIRS[0] + ".ref.exr")):
            return
        hdr_driver = os.path.join(tmp, "hdr_driver")
        with open(hdr_driver + ".cpp", "w") as f:
            f.write(HDR_DRIVER)
        subprocess.run(["g++", "-std=c++17", "-O2", "-fopenmp", "-I", args.flip_repo, "-o",
                        hdr_driver, hdr_driver + ".cpp"], check=True)
        print("\nNVlabs flip tool, HDR-FLIP (flip -r REF.exr -t TEST.exr [-cstart C -cstop C])")
        for name in HDR_PAIRS:
            ref, test = (os.path.join(args.pairs, name + s) for s in (".ref.exr", ".test.exr"))
            given = ["-cstart", HDR_RANGES[name][0], "-cstop", HDR_RANGES[name][1]] \
                if name in HDR_RANGES else []
            for ppd in ("67", "30"):
                out = subprocess.run([tool, "-r", ref, "-t", test, "-ppd", ppd, "-v", "2",
                                      "--no-error-map", "--no-exposure-map"] + given,
                                     check=True, capture_output=True, text=True, cwd=tmp).stdout
                fields = {k.strip(): v.split()[0] for k, v in
                          (line.split(":", 1) for line in out.splitlines() if ":" in line)}
                print(f"{name:16s} ppd {ppd}: exposures {fields['Start exposure']} to "
                      f"{fields['Stop exposure']}, {fields['Number of exposures']}; "
                      f"mean {fields['Mean']}")
            # "inf": FLIP.h computes the range itself, as the tool did.
            start, stop = HDR_RANGES.get(name, ("inf", "inf"))
            pixels = [str(v) for n, x, y in HDR_PIXELS if n == name for v in (x, y)]
            out = subprocess.run([hdr_driver, ref, test, "67", start, stop] + pixels, check=True,
                                 capture_output=True, text=True).stdout
            print(out.strip())


if __name__ == "__main__":
    sys.exit(main())
