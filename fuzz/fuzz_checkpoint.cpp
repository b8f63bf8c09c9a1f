// libFuzzer target: the checkpoint reader (read_checkpoint, then the integrator's own state
// through restore_integrator), as `sinew run --resume` uses them, for the energy-limited scene
// tests/data/checkpoint_scene (its checkpoints, in fuzz/seeds/fuzz_checkpoint, carry that
// scene's fingerprints, so mutations get past the fingerprint checks to the state, the frame
// records and the multipliers).
#include "support.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/checkpoint.hpp"

namespace {

struct Resumable {
  Resumable()
      : scene(sinew::load_scene(SINEW_CHECKPOINT_SCENE)),
        model(sinew::build_model(scene)),
        fingerprint(sinew::fingerprint_run(scene)) {}
  sinew::Scene scene;
  sinew::Model model;
  sinew::RunFingerprint fingerprint;
};

Resumable& resumable() {
  static Resumable r;
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Resumable& r = resumable();
  const auto path = sinew::fuzz::write_input(data, size, "checkpoint.json");
  sinew::fuzz::expect_clean(
      [&] {
        const sinew::Checkpoint c = sinew::read_checkpoint(path.parent_path(), r.fingerprint, *r.model.integrator,
                                                           r.model.initial.x.size(), r.scene.frames);
        sinew::restore_integrator(*r.model.integrator, c, path.parent_path());
      },
      path);
  return 0;
}
