#!/usr/bin/python3
"""Prints the reference values pinned in compare/*_test.cpp, from independent implementations.

1. Write the test pairs (8-bit PNGs, exactly the pixels the tests use):
     TWINRENDER_WRITE_TEST_PAIRS=/tmp/pairs \
       build/compare/twinrender_compare_tests --gtest_filter=ReferencePairs.*
2. /usr/bin/python3 compare/testdata/reference_values.py /tmp/pairs [--flip-repo DIR]

PSNR and SSIM come from scikit-image (Debian 12: python3-skimage 0.19.3, numpy 1.24.2).
With --flip-repo (a checkout of github.com/NVlabs/flip, v1.6 at commit 1eb247c), the script
builds NVlabs' C++ flip tool and prints the mean it reports for each pair at 67 and 30 pixels
per degree (`flip -r REF.png -t TEST.png -ppd 67 -v 1`), then error-map values at a few pixels
from FLIP::evaluate() in that repository's FLIP.h (a small driver, below, that loads the PNGs
as the tool does).
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


if __name__ == "__main__":
    sys.exit(main())
