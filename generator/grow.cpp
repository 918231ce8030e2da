// Model dispatch.
#include "generator/grow.h"

#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "generator/models/fractal/fractal.h"
#include "generator/models/lsystem/lsystem.h"
#include "generator/models/treemaker/treemaker.h"
#include "generator/models/weber_penn/weber_penn.h"

namespace arbor::generator {

void refuse_estimate(bool force, double estimate, double limit, const char* subject,
                     const char* things) {
  if (force || !(estimate > limit)) return;
  char buf[256];
  if (std::isfinite(estimate)) {
    std::snprintf(buf, sizeof buf, "%s about %.3g %s (limit %.3g); use --force to grow it anyway",
                  subject, estimate, things, limit);
  } else {
    std::snprintf(buf, sizeof buf,
                  "%s more than 1e308 %s (limit %.3g); use --force to grow it anyway", subject,
                  things, limit);
  }
  throw RuntimeFailure(buf);
}

void refuse_growth(bool force, double count, double limit, const char* subject,
                   const char* things) {
  if (force || !(count > 2.0 * limit)) return;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %.0f %s; use --force to grow it anyway", subject, count,
                things);
  throw RuntimeFailure(buf);
}

namespace {

Skeleton grow_model(const Species& species, const GrowOptions& options) {
  switch (species.model()) {
    case Model::LSystem: return grow_lsystem(species.lsystem(), options);
    case Model::Fractal: return grow_fractal(species.fractal(), options);
    case Model::TreeMaker: return grow_treemaker(species.treemaker(), options);
    case Model::SkeletonFile:
      return species.skeleton();  // a skeleton file is the tree itself: seed and time do nothing
    case Model::WeberPenn:
    default: return grow_weber_penn(species.weber_penn(), options);
  }
}

}  // namespace

Skeleton grow_tree(const Species& species, const GrowOptions& options) {
  Skeleton sk = grow_model(species, options);
  const std::string outside = scale_problem(sk);
  if (!outside.empty()) {
    throw InputError({species.path, 0, 0}, "the grown tree is out of scale: " + outside +
                                               "; the species' sizes or growth compound past what "
                                               "arbor's geometry can hold");
  }
  // Every model must grow a valid skeleton; one that does not is arbor's bug, never written out.
  const std::string problem = validate(sk);
  if (!problem.empty())
    check_failed(("the grown skeleton is valid: " + problem).c_str(), __FILE__, __LINE__);
  return sk;
}

}  // namespace arbor::generator
