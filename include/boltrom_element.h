#ifndef BOLTROM_ELEMENT_H
#define BOLTROM_ELEMENT_H
/* Element kernels: pure functions of nodal coordinates and material constants.
   They know nothing about meshes, parallelism or solvers.

   Hexahedron node order (same as gmsh and VTK): nodes 0-3 are the face zeta = -1 in the
   order (xi,eta) = (-1,-1), (1,-1), (1,1), (-1,1); nodes 4-7 are the face zeta = +1 in the
   same order. X is node-major: X[3*a + d] is coordinate d of node a. Element vectors are
   node-major too: entry 3*a + d is displacement component d of node a. Element matrices are
   24 x 24, row-major. */
#include <petscsys.h>

typedef enum {
  HEX8_FULL         = 0, /* trilinear, 2x2x2 Gauss: locks in bending on coarse meshes */
  HEX8_INCOMPATIBLE = 1  /* trilinear + 9 incompatible bubble modes (Wilson-Taylor), condensed */
} Hex8Formulation;

/* Isotropic linear elasticity: 6x6 Voigt matrix, engineering shear strains,
   Voigt order xx, yy, zz, yz, xz, xy. */
PetscErrorCode ElasticityVoigt(PetscReal E, PetscReal nu, PetscReal D[36]);

/* Stiffness matrix (symmetric, 24x24). Errors with PETSC_ERR_ARG_OUTOFRANGE if det J <= 0 at a
   Gauss point (inverted or degenerate element). */
PetscErrorCode Hex8Stiffness(const PetscReal X[24], PetscReal E, PetscReal nu, Hex8Formulation form, PetscReal Ke[576]);

/* Consistent mass matrix (24x24) of density rho with 2x2x2 Gauss (exact for trilinear maps). */
PetscErrorCode Hex8Mass(const PetscReal X[24], PetscReal rho, PetscReal Me[576]);

/* Volume of the trilinear element (2x2x2 Gauss, exact). */
PetscErrorCode Hex8Volume(const PetscReal X[24], PetscReal *volume);

/* Stress (Voigt, 6 per point) at the 8 Gauss points (point g at natural coordinates
   (1/sqrt 3) x those of node g) for nodal displacements u[24]. For the
   incompatible formulation the internal modes are recovered from the condensation. */
PetscErrorCode Hex8Stress(const PetscReal X[24], const PetscReal u[24], PetscReal E, PetscReal nu, Hex8Formulation form, PetscReal sigma[48]);

/* Contact element between two matching quadrilateral faces a and b (node i of a coincides
   with node i of b). Xa: 4 nodes x 3 coordinates of face a, in cyclic order. The relative
   displacement g = u_b - u_a is interpolated with bilinear shape functions; the penalty
   traction is epsN (g.n) n + epsT (g - (g.n) n), with n the unit normal of face a at the
   Gauss point (2x2 Gauss on the face). The 24x24 matrix acts on the element vector
   [u_a (4 nodes x 3), u_b (4 nodes x 3)]: Kc = int B' P B dA with B = [-N, N]. */
PetscErrorCode QuadPairPenaltyStiffness(const PetscReal Xa[12], PetscReal epsN, PetscReal epsT, PetscReal Kc[576]);

/* The same, with only the Gauss points flagged in active[4] contributing. */
PetscErrorCode QuadPairPenaltyStiffnessActive(const PetscReal Xa[12], PetscReal epsN, PetscReal epsT, const PetscBool active[4], PetscReal Kc[576]);

/* Gauss point data of the face: shape values N[4*gp + a], area weights w[gp] (Gauss weight x
   surface Jacobian), unit normals n[3*gp + k] (right-hand rule of the node order). */
PetscErrorCode QuadGaussPoints(const PetscReal Xa[12], PetscReal N[16], PetscReal w[4], PetscReal n[12]);

/* Nodal quadrature of the face (weight 1 at each corner of the reference square): the points
   sit at the nodes, so N[4*a + b] = delta_ab, w[a] is the surface Jacobian at node a and n the
   unit normal there. On a pair meshed node to node each point then constrains one node pair. */
PetscErrorCode QuadNodalPoints(const PetscReal Xa[12], PetscReal N[16], PetscReal w[4], PetscReal n[12]);

/* The pair's 24x24 penalty matrix from given point data (shape values, weights, normals, as
   QuadGaussPoints or QuadNodalPoints give them), active points only, with no tangential
   penalty at the points flagged in released (may be NULL). */
PetscErrorCode QuadPairPenaltyStiffnessPoints(const PetscReal N[16], const PetscReal w[4], const PetscReal n[12], PetscReal epsN, PetscReal epsT, const PetscBool active[4], const PetscBool released[4], const PetscReal slipDir[16], PetscReal Kc[576]);

/* Area of the bilinear quad face (2x2 Gauss). */
PetscErrorCode QuadArea(const PetscReal X[12], PetscReal *area);

#endif
