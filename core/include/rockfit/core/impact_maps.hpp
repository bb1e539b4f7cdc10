// Impact maps of Várkonyi, Kocsis & Ther (2021): planar AVRFs (3)–(6), the general map (18), the edge
// map (19)–(20), the facet map (18)+(21) with feasibility (22)–(23), the unified facet map with the
// no-spin postulate (24), energy (26) and the bounds (25), (27). docs/design.md §3, including its errata.
//
// Every function is pure: it takes a const Block and the impact configuration and returns a value.
// Numerical trouble is a status, never a NaN. This header includes one header per concept:
#pragma once

#include "rockfit/core/contact.hpp"             // Contact
#include "rockfit/core/edge_impact.hpp"         // EdgeImpact, EdgeImpactAttitude, EdgeImpactSingularLambdas
#include "rockfit/core/facet_impact.hpp"        // FacetImpact, FacetTauRule
#include "rockfit/core/facet_impact_regions.hpp"  // EvaluateFacetRegions (Fig. 11)
#include "rockfit/core/general_impact_map.hpp"  // ImpactStatus, ImpactGeometry, GeneralImpactMap, (14), (26)
#include "rockfit/core/impact_map_derivatives.hpp"  // EdgeImpactDerivatives, FacetImpactDerivatives
#include "rockfit/core/impact_outcome.hpp"      // ImpactOutcome, FacetCandidate
#include "rockfit/core/planar_avrf.hpp"         // (3)–(6)
