// Time of impact along +s computed by other libraries (the peers of the core
// benchmark), on the same hulls and queries as mddual::toi():
//
//   bullet_gjk         btGjkConvexCast        \  btConvexHullShape (double
//   bullet_subsimplex  btSubsimplexConvexCast /  precision, margin 0) and
//                                                btVoronoiSimplexSolver
//   fcl_naive          fcl::continuousCollide, CCDC_NAIVE: FCL's default
//                      request (10 samples of the motion, discrete GJK at each)
//   fcl_ca_libccd      fcl::continuousCollide, CCDC_CONSERVATIVE_ADVANCEMENT,
//   fcl_ca_indep       with GST_LIBCCD / GST_INDEP GJK
//
// All FCL variants use fcl::Convex<double> built from the vertices and the
// (merged, counter-clockwise) faces of mddual::ConvexPolytope and
// ccd_motion_type = CCDM_TRANS. Every peer casts B from its pose along
// cast_length * s (A static) and reports toi = fraction * cast_length, or
// +infinity when it reports no contact. This header includes no third-party
// header: the peers live behind a small interface (peers.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mddual/polytope.h"
#include "scene.h"

namespace mddual::bench {

class ToiPeer {
 public:
  virtual ~ToiPeer() = default;
  virtual const std::string& name() const = 0;
  /// Forward time of impact of q (world units): 0 if the peer reports contact
  /// at the start, +infinity for no contact within the cast. Throws
  /// std::runtime_error when the peer reports a failure.
  virtual double toi(const Query& q) = 0;
};

/// Names of the available peers, in the order makePeers() returns them.
std::vector<std::string> peerNames();

/// Builds the peers listed in `names` (all if empty) for polytopes a and b
/// (body frames), built once. cast_length must exceed every contact distance
/// of the scene.
std::vector<std::unique_ptr<ToiPeer>> makePeers(const ConvexPolytope& a, const ConvexPolytope& b, double cast_length,
                                                const std::vector<std::string>& names = {});

/// A short description of each peer's settings (for the JSON summary).
std::string peerSettings(const std::string& name);

// ---- Penetration depth peers (bench_pd.cpp) ---------------------------------------
//
//   fcl_mpr_libccd      fcl::collide, enable_contact, GST_LIBCCD: FCL 0.7 answers a
//                       Convex-Convex contact with libccd's MPR penetration
//                       (ccdMPRPenetration), a depth along one direction
//   fcl_epa_indep       fcl::collide, enable_contact, GST_INDEP: FCL's own GJK + EPA
//   fcl_epa_libccd      fcl::distance with enable_signed_distance, GST_LIBCCD:
//                       libccd's GJK + EPA (ccdGJKSignedDist); depth = -distance
//   bullet_epa          btGjkEpaSolver2::Penetration (double precision, margin 0)
//
// All on fcl::Convex / btConvexHullShape built from the same hulls.

/// What a peer reports for one posed pair.
struct PdAnswer {
  bool collide = false;  ///< the peer reports a collision
  double depth = 0.0;    ///< its penetration depth (0 when not colliding)
};

class PdPeer {
 public:
  virtual ~PdPeer() = default;
  virtual const std::string& name() const = 0;
  /// Throws std::runtime_error when the peer reports a failure.
  virtual PdAnswer penetration(const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB) = 0;
};

std::vector<std::string> pdPeerNames();
std::vector<std::unique_ptr<PdPeer>> makePdPeers(const ConvexPolytope& a, const ConvexPolytope& b,
                                                 const std::vector<std::string>& names = {});
std::string pdPeerSettings(const std::string& name);

}  // namespace mddual::bench
