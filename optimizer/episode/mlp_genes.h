// The genome of a neural network (--controller mlp:H, mlp:H1,H2): the
// clock period and one gene per weight ("period", "w0", "w1", ...,
// network_genes.h) for the robot's joint count, then any body genes of the
// user's genome but module_count, which would change the joint count the
// network's size is made for (docs/nn.md).
#pragma once

#include <string>
#include <vector>

#include "nn_controller/mlp_network.h"
#include "optimizer/episode/controller_spec.h"
#include "optimizer/search/genome.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

// The shape of `controller` (an mlp kind with its joints resolved): joint
// angles and speeds and the clock in, one target per hinge out.
MlpShape MlpShapeOf(const ControllerSpec& controller);

// Sets controller.joints to the hinge count of the genome's robot (`robot`,
// empty: the first) in `scenario`. Throws GenomeError when there is no
// such robot or it has no hinge.
void ResolveMlpJoints(ControllerSpec* controller, const Scenario& scenario,
                      const std::string& robot);

// The network's genes, then the body genes of `user` (nullptr: none).
// Throws GenomeError naming a gene that is not a body gene, module_count,
// or a network too large (MlpShape's bounds).
GenomeSpec MlpGenome(const ControllerSpec& controller, const GenomeSpec* user);

// The network of one individual. Throws GenomeError when the genome lacks
// the period or a weight gene, or its weights do not follow each other
// (w0, w1, ... in order, as MlpGenome lays them out).
MlpNetwork MlpNetworkOfGenome(const MlpShape& shape, const GenomeSpec& spec,
                              const Genome& genome);

}  // namespace mrsim
