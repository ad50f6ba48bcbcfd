// convergence.cpp: error against run time (issue 6). For each scene it renders a
// converged reference once (seed 1, cached as <out>/<scene>.ref-seed1.exr, regenerated
// when missing), then renders with increasing time budgets and reports, per budget, the
// true relative RMSE against the reference next to the renderer's own estimate, their
// ratio, and the fitted log-log slope of error against time (-0.5 for unbiased Monte
// Carlo). Writes <out>/<scene>.csv and, when gnuplot is installed, <out>/<scene>.png
// (-sobol in the names with --sampler sobol).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>

#include "film/exr_output.h"
#include "film/film_error.h"
#include "ocl/device.h"
#include "render/renderer.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"

namespace fs = std::filesystem;
using namespace rd;

namespace {

Scene loadScene(const std::string& path) {
    rib::Diagnostics diag(&std::cerr);
    RibBuilder builder(diag, path);
    rib::readFile(path, builder, diag);
    if (diag.errorCount() || builder.scenes().empty())
        throw std::runtime_error("cannot load " + path);
    return builder.scenes().front();
}

// sqrt(mean over pixels and colour channels of (img - ref)^2) / mean(ref): the same
// definition as estimateFilmErrors, so the two can be compared directly.
double relativeRmse(const std::vector<Rgba>& img, const std::vector<Rgba>& ref) {
    double se = 0, sum = 0;
    for (size_t i = 0; i < img.size(); ++i) {
        const float* a = &img[i].r;
        const float* b = &ref[i].r;
        for (int c = 0; c < 3; ++c) {
            se += double(a[c] - b[c]) * (a[c] - b[c]);
            sum += b[c];
        }
    }
    double n = 3.0 * double(img.size());
    return std::sqrt(se / n) / (sum / n);
}

double fitSlope(const std::vector<double>& x, const std::vector<double>& y) {
    double n = double(x.size()), sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"RayDrive convergence benchmark: true vs estimated error against time"};
    std::vector<std::string> scenes;
    std::string outDir = "convergence-out";
    std::vector<double> budgets{0.25, 0.5, 1, 2, 4, 8};
    int refSide = 48;
    int repeats = 3;
    std::string sampler = "independent";
    app.add_option("scenes", scenes, "RIB files")->required();
    app.add_option("--out", outDir, "output folder (reference cache, CSV, PNG)");
    // (one comma-separated list, read as one string: with CLI11's delimiter the list's
    // items count as several values, and a vector option swallows the scenes after it)
    std::string budgetList;
    app.add_option("--budgets", budgetList, "time budgets in seconds, e.g. 0.5,1,2");
    app.add_option("--ref-side", refSide, "reference: side x side samples per pixel");
    app.add_option("--repeats", repeats, "renders per budget (the median is reported)");
    app.add_option("--sampler", sampler, "the budget renders' sampler (the reference's: independent)")
        ->check(CLI::IsMember({"independent", "sobol"}));
    CLI11_PARSE(app, argc, argv);
    if (!budgetList.empty()) {
        budgets.clear();
        std::stringstream in(budgetList);
        for (std::string item; std::getline(in, item, ',');) {
            char* end = nullptr;
            const double v = std::strtod(item.c_str(), &end);
            if (item.empty() || *end != '\0' || !(v > 0)) {
                std::fprintf(stderr, "--budgets: not a positive number: '%s'\n", item.c_str());
                return 2;
            }
            budgets.push_back(v);
        }
    }
    fs::create_directories(outDir);
    ClContext ctx(selectDevice(""));
    std::printf("device: %s\n", ctx.name().c_str());

    for (const std::string& path : scenes) {
        Scene scene = loadScene(path);
        std::string stem = fs::path(path).stem().string();
        // (seed 1: the reference shares no sample with the renders it judges, seed 0)
        std::string refPath = outDir + "/" + stem + ".ref-seed1.exr";
        std::vector<Rgba> ref;
        double refError = 0;
        int w = 0, h = 0;
        if (fs::exists(refPath)) {
            ref = readExr(refPath, w, h);
            std::ifstream(refPath + ".err") >> refError;
        }
        if (ref.empty() || w != scene.camera.width || h != scene.camera.height) {
            Scene rs = scene;
            rs.camera.pixelSamples[0] = rs.camera.pixelSamples[1] = float(refSide);
            rs.render.firstPassBlock = 1;
            rs.render.pixelError = 1e-9f;  // every pixel gets all the samples
            Film film;
            rib::Diagnostics rdiag(&std::cerr);
            RenderSettings refSettings;
            refSettings.seed = 1;
            refSettings.sobol = 0;  // independent, whatever the renderer's default
            RenderStats st = Renderer(ctx, refSettings).render(rs, film, rdiag);
            ref = film.resolve();
            refError = st.estimatedError;
            writeExr(refPath, film.width, film.height, ref, {});
            std::ofstream(refPath + ".err") << refError << "\n";
            std::printf("%s: reference %dx%d spp in %.1f s, its estimated error %.2e\n",
                        stem.c_str(), refSide, refSide, st.elapsedSec, refError);
        }
        std::printf("\n%s  (true error has the reference's own %.2e removed in quadrature)\n",
                    stem.c_str(), refError);
        std::printf("%8s %9s %12s %11s %11s %7s\n", "budget_s", "elapsed_s", "rays",
                    "true_err", "est_err", "est/true");
        const std::string runName = stem + (sampler == "sobol" ? "-sobol" : "");
        std::ofstream csv(outDir + "/" + runName + ".csv");
        csv << "budget_s,elapsed_s,rays,true_error,estimated_error\n";
        std::vector<double> times, trues, ratios;
        {  // an untimed render first: the first budget's render would build the program
            RenderSettings s;
            s.timeBudget = 0.05;
            s.sobol = sampler == "sobol" ? 1 : 0;
            Film film;
            rib::Diagnostics rdiag(&std::cerr);
            Renderer(ctx, s).render(scene, film, rdiag);
        }
        for (double budget : budgets) {
            struct Run {
                double elapsed, truth, est;
                uint64_t rays;
            };
            std::vector<Run> runs;
            for (int r = 0; r < repeats; ++r) {
                RenderSettings s;
                s.timeBudget = budget;
                s.sobol = sampler == "sobol" ? 1 : 0;
                Film film;
                rib::Diagnostics rdiag(&std::cerr);
                RenderStats st = Renderer(ctx, s).render(scene, film, rdiag);
                double measured = relativeRmse(film.resolve(), ref);
                double truth = std::sqrt(std::max(0.0, measured * measured - refError * refError));
                runs.push_back({st.elapsedSec, truth, st.estimatedError, st.totalRays()});
            }
            std::sort(runs.begin(), runs.end(),
                      [](const Run& a, const Run& b) { return a.truth < b.truth; });
            const Run& m = runs[runs.size() / 2];
            std::printf("%8.2f %9.3f %12llu %11.3e %11.3e %7.2f\n", budget, m.elapsed,
                        (unsigned long long)m.rays, m.truth, m.est, m.est / m.truth);
            csv << budget << "," << m.elapsed << "," << m.rays << "," << m.truth << ","
                << m.est << "\n";
            if (m.truth > 0 && m.est > 0) {
                times.push_back(m.elapsed);
                trues.push_back(m.truth);
                ratios.push_back(m.est / m.truth);
            }
        }
        if (times.size() >= 2) {
            auto [lo, hi] = std::minmax_element(ratios.begin(), ratios.end());
            std::printf("fitted slope of true error vs time: %.3f (unbiased MC: -0.5); "
                        "est/true in [%.2f, %.2f] (goal within [0.5, 2])\n",
                        fitSlope(times, trues), *lo, *hi);
        }
        csv.close();
        if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
            std::string png = outDir + "/" + runName + ".png";
            std::string cmd =
                "gnuplot -e \"set terminal pngcairo size 800,600 noenhanced; set output '" + png +
                "'; set logscale xy; set grid; set key top right; set datafile separator ',';"
                " set xlabel 'elapsed (s)'; set ylabel 'relative RMSE'; set title '" + runName +
                ": error against time'; plot '" + outDir + "/" + runName +
                ".csv' using 2:4 skip 1 with linespoints title 'true', '' using 2:5 skip 1 "
                "with linespoints title 'estimated'\"";
            if (std::system(cmd.c_str()) == 0) std::printf("plot: %s\n", png.c_str());
        }
    }
    return 0;
}
