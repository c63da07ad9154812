// A basalt impactor hitting a basalt target obliquely, simulated by OpenSPH's SPH solver with
// strength and fracture, the set-up of OpenSPH's own collision problem
// (cli/problems/collision/Collision.cpp) at kilometre scale and without self-gravity.
// Writes OpenSPH's binary output (.ssf) every output interval, with the quantities a renderer
// needs (position with velocity and acceleration, mass, density, body flag) rather than the
// solver's whole state (stress tensor, damage and fracture quantities, ...), which would triple
// the files' size.
//
//   collision OUT_DIR [key=value ...]
//
// Keys (SI units): target_radius, impactor_radius, target_particles, speed, angle_deg,
// contact_time, frames, interval. The impactor gets as many particles as its volume holds at the
// target's spacing, so both bodies have the same resolution.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>

#include "Sph.h"

using namespace Sph;

namespace {

struct Parameters {
    Float targetRadius = 5.e3_f;     // m
    Float impactorRadius = 2.5e3_f;  // m
    int targetParticles = 8000;      // requested; the hexagonal lattice gives about as many
    Float speed = 4.e3_f;            // m/s, impactor relative to target
    Float angleDeg = 30._f;          // between the velocity and the line of centres at contact
    Float contactTime = 0.25_f;      // s, until the surfaces would touch
    int frames = 41;                 // output files, the first at t = 0
    Float interval = 0.15_f;         // s between output files
};

Parameters parse(int argc, char** argv) {
    Parameters p;
    std::map<std::string, Float*> floats = {{"target_radius", &p.targetRadius},
                                            {"impactor_radius", &p.impactorRadius},
                                            {"speed", &p.speed},
                                            {"angle_deg", &p.angleDeg},
                                            {"contact_time", &p.contactTime},
                                            {"interval", &p.interval}};
    std::map<std::string, int*> ints = {{"target_particles", &p.targetParticles},
                                        {"frames", &p.frames}};
    for (int i = 2; i < argc; ++i) {
        const std::string arg = argv[i];
        const std::size_t eq = arg.find('=');
        const std::string key = arg.substr(0, eq);
        if (eq == std::string::npos || (!floats.count(key) && !ints.count(key))) {
            std::cerr << "collision: unknown argument '" << arg << "'\n";
            std::exit(2);
        }
        const std::string value = arg.substr(eq + 1);
        if (floats.count(key))
            *floats[key] = std::stod(value);
        else
            *ints[key] = std::stoi(value);
    }
    return p;
}

// Prints the run's progress every `period` seconds of simulated time.
class ProgressLog : public PeriodicTrigger {
  public:
    explicit ProgressLog(const Float period) : PeriodicTrigger(period, 0._f) {}

    AutoPtr<ITrigger> action(Storage& storage, Statistics& stats) override {
        const Float t = stats.get<Float>(StatisticsId::RUN_TIME);
        const Float dt = stats.get<Float>(StatisticsId::TIMESTEP_VALUE);
        const int step = stats.get<int>(StatisticsId::INDEX);
        const double wall = std::chrono::duration<double>(Clock::now() - mStart).count();
        std::cout << "t = " << t << " s, step " << step << ", dt = " << dt << " s, "
                  << storage.getParticleCnt() << " particles, " << wall << " s wall" << std::endl;
        return nullptr;
    }

  private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point mStart = Clock::now();
};

// OpenSPH's BinaryOutput of a storage holding only the quantities named above, per material
// (the materials are shared, so the files carry their parameters as a full output does).
class CompactOutput : public IOutput {
  public:
    CompactOutput(const OutputFile& fileMask, Array<SharedPtr<IMaterial>> materials)
        : IOutput(fileMask), mBinary(fileMask), mMaterials(std::move(materials)) {}

    Expected<Path> dump(const Storage& storage, const Statistics& stats) override {
        Storage compact;
        for (Size m = 0; m < storage.getMaterialCnt(); ++m) compact.merge(part(storage, m));
        return mBinary.dump(compact, stats);
    }

  private:
    template <typename T>
    static Array<T> gather(ArrayView<const T> values, IndexSequence sequence) {
        Array<T> out;
        for (Size i : sequence) out.push(values[i]);
        return out;
    }

    Storage part(const Storage& storage, const Size m) const {
        const IndexSequence seq = storage.getMaterial(m).sequence();
        Storage out(mMaterials[m]);
        const Quantity& r = storage.getQuantity(QuantityId::POSITION);
        Quantity& outR = out.insert<Vector>(QuantityId::POSITION, OrderEnum::SECOND,
                                            gather<Vector>(r.getValue<Vector>(), seq));
        outR.getDt<Vector>() = gather<Vector>(r.getDt<Vector>(), seq);
        outR.getD2t<Vector>() = gather<Vector>(r.getD2t<Vector>(), seq);
        out.insert<Float>(QuantityId::MASS, OrderEnum::ZERO,
                          gather<Float>(storage.getValue<Float>(QuantityId::MASS), seq));
        out.insert<Float>(QuantityId::DENSITY, OrderEnum::ZERO,
                          gather<Float>(storage.getValue<Float>(QuantityId::DENSITY), seq));
        out.insert<Size>(QuantityId::FLAG, OrderEnum::ZERO,
                         gather<Size>(storage.getValue<Size>(QuantityId::FLAG), seq));
        return out;
    }

    BinaryOutput mBinary;
    Array<SharedPtr<IMaterial>> mMaterials;
};

class Collision : public IRun {
  public:
    Collision(const Parameters& p, const std::string& outDir)
        : mP(p), mOutDir(String::fromAscii(outDir.c_str())) {
        // As OpenSPH's collision problem, without self-gravity (the escape speed of a 5 km
        // basalt body is about 5 m/s, negligible over seconds) and with the default evolution of
        // the smoothing length (continuity equation), so h grows where the debris expands.
        // Half an interval past the last output time, so the run loop writes the last file (a file
        // written after the loop would carry the start time of the last step in its header).
        const Float endTime = (Float(p.frames) - 0.5_f) * p.interval;
        settings.set(RunSettingsId::RUN_NAME, String("Basalt impact"))
            .set(RunSettingsId::TIMESTEPPING_INTEGRATOR, TimesteppingEnum::PREDICTOR_CORRECTOR)
            .set(RunSettingsId::TIMESTEPPING_INITIAL_TIMESTEP, 1.e-4_f)
            .set(RunSettingsId::TIMESTEPPING_MAX_TIMESTEP, 0.1_f)
            .set(RunSettingsId::TIMESTEPPING_CRITERION, TimeStepCriterionEnum::COURANT)
            .set(RunSettingsId::TIMESTEPPING_COURANT_NUMBER, 0.2_f)
            .set(RunSettingsId::RUN_END_TIME, endTime)
            .set(RunSettingsId::RUN_OUTPUT_INTERVAL, p.interval)
            .set(RunSettingsId::SPH_SOLVER_FORCES, ForceEnum::PRESSURE | ForceEnum::SOLID_STRESS)
            .set(RunSettingsId::SPH_SOLVER_TYPE, SolverEnum::ASYMMETRIC_SOLVER)
            .set(RunSettingsId::SPH_FINDER, FinderEnum::KD_TREE)
            .set(RunSettingsId::SPH_DISCRETIZATION, DiscretizationEnum::STANDARD)
            .set(RunSettingsId::SPH_AV_TYPE, ArtificialViscosityEnum::STANDARD)
            .set(RunSettingsId::SPH_AV_ALPHA, 1.5_f)
            .set(RunSettingsId::SPH_AV_BETA, 3._f)
            .set(RunSettingsId::SPH_STRAIN_RATE_CORRECTION_TENSOR, true)
            .set(RunSettingsId::RUN_THREAD_GRANULARITY, 100)
            .set(RunSettingsId::FINDER_LEAF_SIZE, 20);
        scheduler = Factory::getScheduler(settings);
    }

  protected:
    void setUp(SharedPtr<Storage> storage) override {
        // Basalt (OpenSPH's default material): Tillotson equation of state, von Mises yielding,
        // Grady-Kipp fracture with Weibull flaws; particles on a hexagonal lattice.
        BodySettings target;
        target.set(BodySettingsId::ENERGY, 10._f)
            .set(BodySettingsId::ENERGY_RANGE, Interval(0._f, INFTY))
            .set(BodySettingsId::EOS, EosEnum::TILLOTSON)
            .set(BodySettingsId::RHEOLOGY_DAMAGE, FractureEnum::SCALAR_GRADY_KIPP)
            .set(BodySettingsId::RHEOLOGY_YIELDING, YieldingEnum::VON_MISES)
            .set(BodySettingsId::DISTRIBUTE_MODE_SPH5, false)
            .set(BodySettingsId::INITIAL_DISTRIBUTION, DistributionEnum::HEXAGONAL)
            .set(BodySettingsId::PARTICLE_COUNT, mP.targetParticles);
        const Float volumeRatio = std::pow(mP.impactorRadius / mP.targetRadius, 3._f);
        BodySettings impactor = target;
        impactor.set(BodySettingsId::PARTICLE_COUNT,
                     int(std::round(mP.targetParticles * volumeRatio)));

        SharedPtr<IMaterial> targetMaterial(Factory::getMaterial(target));
        SharedPtr<IMaterial> impactorMaterial(Factory::getMaterial(impactor));
        InitialConditions ic(settings);
        ic.addMonolithicBody(*storage, SphericalDomain(Vector(0._f), mP.targetRadius),
                             targetMaterial);

        // The impactor flies along -x; at contact the line of centres makes `angle` with it.
        const Float angle = mP.angleDeg * DEG_TO_RAD;
        const Float reach = mP.targetRadius + mP.impactorRadius;
        const Vector origin(reach * std::cos(angle) + mP.speed * mP.contactTime,
                            reach * std::sin(angle), 0._f);
        BodyView impactorView = ic.addMonolithicBody(
            *storage, SphericalDomain(origin, mP.impactorRadius), impactorMaterial);
        impactorView.addVelocity(Vector(-mP.speed, 0._f, 0._f));

        output =
            makeAuto<CompactOutput>(OutputFile(Path(mOutDir) / Path("collision_%d.ssf")),
                                    Array<SharedPtr<IMaterial>>{targetMaterial, impactorMaterial});
        logWriter = makeAuto<NullLogWriter>();
        triggers.pushBack(makeAuto<ProgressLog>(mP.interval));
        printSetUp(*storage);
    }

    void tearDown(const Storage&, const Statistics&) override {}

  private:
    void printSetUp(const Storage& storage) const {
        ArrayView<const Size> flag = storage.getValue<Size>(QuantityId::FLAG);
        ArrayView<const Vector> r = storage.getValue<Vector>(QuantityId::POSITION);
        Size counts[2] = {0, 0};
        Float hSum[2] = {0._f, 0._f};
        for (Size i = 0; i < r.size(); ++i) {
            counts[flag[i]]++;
            hSum[flag[i]] += r[i][H];
        }
        for (int b = 0; b < 2; ++b)
            std::cout << (b == 0 ? "target" : "impactor") << ": " << counts[b]
                      << " particles, mean h = " << hSum[b] / counts[b] << " m" << std::endl;
    }

    Parameters mP;
    String mOutDir;
};

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: collision OUT_DIR [key=value ...]\n";
        return 2;
    }
    try {
        const Parameters p = parse(argc, argv);
        Collision run(p, argv[1]);
        Storage storage;
        const auto start = std::chrono::steady_clock::now();
        run.run(storage);
        std::cout << "run time "
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                  << " s" << std::endl;
    } catch (const std::exception& e) {
        std::cerr << "collision: " << e.what() << std::endl;
        return 1;
    }
    return 0;
}
