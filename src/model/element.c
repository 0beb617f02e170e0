/* Element kernels for 8-node hexahedra and quad-pair penalty contact (see boltrom_element.h).
   No allocation: all work arrays live on the stack, these run once per element. */
#include <boltrom_element.h> /* petscsys.h must precede petscblaslapack.h */
#include <petscblaslapack.h>

#define HEX8_NX         11                     /* 8 nodes + 3 incompatible (bubble) modes */
#define HEX8_LDX        (3 * HEX8_NX)          /* leading dimension of the extended 33x33 matrix */
#define GAUSS_PT        0.57735026918962576451 /* 1/sqrt(3): 2-point Gauss, weights 1 */
#define HEX8_DEGENERATE 1e-12                  /* det J / (|J row 0| |J row 1| |J row 2|) at or below this: degenerate */

/* Natural coordinates of the nodes; Gauss point g sits at GAUSS_PT * hexNode[g] (the stress
   output of Hex8Stress follows this order). */
static const PetscReal hexNode[8][3] = {
  {-1, -1, -1},
  {1,  -1, -1},
  {1,  1,  -1},
  {-1, 1,  -1},
  {-1, -1, 1 },
  {1,  -1, 1 },
  {1,  1,  1 },
  {-1, 1,  1 }
};
static const PetscReal quadNode[4][2] = {
  {-1, -1},
  {1,  -1},
  {1,  1 },
  {-1, 1 }
};

static PetscErrorCode LameConstants(PetscReal E, PetscReal nu, PetscReal *lambda, PetscReal *mu)
{
  PetscFunctionBeginUser;
  PetscCheck(E > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Young's modulus E = %g must be positive", (double)E);
  PetscCheck(nu > -1 && nu < 0.5, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Poisson ratio nu = %g must be in (-1, 0.5)", (double)nu);
  *lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  *mu     = E / (2 * (1 + nu));
  PetscFunctionReturn(0);
}

PetscErrorCode ElasticityVoigt(PetscReal E, PetscReal nu, PetscReal D[36])
{
  PetscReal lambda, mu;
  PetscInt  i, j;

  PetscFunctionBeginUser;
  PetscCall(LameConstants(E, nu, &lambda, &mu));
  for (i = 0; i < 36; i++) D[i] = 0;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) D[6 * i + j] = lambda;
    D[6 * i + i] = lambda + 2 * mu;
    D[6 * (i + 3) + i + 3] = mu; /* engineering shear strains */
  }
  PetscFunctionReturn(0);
}

/* Trilinear shape functions and their natural derivatives dNdxi[3a+i] = dN_a/dxi_i at q. */
static PetscErrorCode Hex8Shape(const PetscReal q[3], PetscReal N[8], PetscReal dNdxi[24])
{
  PetscInt a;

  PetscFunctionBeginUser;
  for (a = 0; a < 8; a++) {
    const PetscReal f0 = 1 + hexNode[a][0] * q[0], f1 = 1 + hexNode[a][1] * q[1], f2 = 1 + hexNode[a][2] * q[2];

    N[a]             = 0.125 * f0 * f1 * f2;
    dNdxi[3 * a + 0] = 0.125 * hexNode[a][0] * f1 * f2;
    dNdxi[3 * a + 1] = 0.125 * hexNode[a][1] * f0 * f2;
    dNdxi[3 * a + 2] = 0.125 * hexNode[a][2] * f0 * f1;
  }
  PetscFunctionReturn(0);
}

/* J[3i+j] = dx_j/dxi_i, its inverse and determinant; errors if det J <= 0. */
static PetscErrorCode Hex8Jacobian(const PetscReal X[24], const PetscReal dNdxi[24], PetscInt gp, PetscReal Jinv[9], PetscReal *detJ)
{
  PetscReal J[9] = {0}, det, idet, scale;
  PetscInt  a, i, j;

  PetscFunctionBeginUser;
  for (a = 0; a < 8; a++)
    for (i = 0; i < 3; i++)
      for (j = 0; j < 3; j++) J[3 * i + j] += dNdxi[3 * a + i] * X[3 * a + j];
  Jinv[0] = J[4] * J[8] - J[5] * J[7];
  Jinv[1] = J[2] * J[7] - J[1] * J[8];
  Jinv[2] = J[1] * J[5] - J[2] * J[4];
  Jinv[3] = J[5] * J[6] - J[3] * J[8];
  Jinv[4] = J[0] * J[8] - J[2] * J[6];
  Jinv[5] = J[2] * J[3] - J[0] * J[5];
  Jinv[6] = J[3] * J[7] - J[4] * J[6];
  Jinv[7] = J[1] * J[6] - J[0] * J[7];
  Jinv[8] = J[0] * J[4] - J[1] * J[3];
  det     = J[0] * Jinv[0] + J[1] * Jinv[3] + J[2] * Jinv[6];
  /* Scaled against the row lengths: a flat element gives det J = O(roundoff), not exactly 0 */
  scale = PetscSqrtReal((J[0] * J[0] + J[1] * J[1] + J[2] * J[2]) * (J[3] * J[3] + J[4] * J[4] + J[5] * J[5]) * (J[6] * J[6] + J[7] * J[7] + J[8] * J[8]));
  PetscCheck(det > HEX8_DEGENERATE * scale, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Hex8: det J = %g (scaled %g) not positive at %s %" PetscInt_FMT " (inverted or degenerate element)", (double)det, (double)(scale > 0 ? det / scale : 0), gp < 0 ? "element centre" : "Gauss point", gp < 0 ? 0 : gp);
  idet = 1 / det;
  for (i = 0; i < 9; i++) Jinv[i] *= idet;
  *detJ = det;
  PetscFunctionReturn(0);
}

/* Physical gradients at Gauss point gp: G[3a+j] = dN_a/dx_j for the 8 nodes and, if
   incompatible, for the 3 bubbles 1 - xi_k^2. Bubble gradients use J0 (element centre) scaled
   by detJ0/detJ (Taylor's correction): their integral vanishes, so the patch test passes on
   distorted meshes. */
static PetscErrorCode Hex8Gradients(const PetscReal X[24], PetscInt gp, PetscBool incompatible, const PetscReal J0inv[9], PetscReal detJ0, PetscReal N[8], PetscReal G[3 * HEX8_NX], PetscReal *detJ)
{
  PetscReal q[3], dNdxi[24], Jinv[9], s;
  PetscInt  a, i, j, k;

  PetscFunctionBeginUser;
  for (i = 0; i < 3; i++) q[i] = GAUSS_PT * hexNode[gp][i];
  PetscCall(Hex8Shape(q, N, dNdxi));
  PetscCall(Hex8Jacobian(X, dNdxi, gp, Jinv, detJ));
  for (a = 0; a < 8; a++)
    for (j = 0; j < 3; j++) G[3 * a + j] = Jinv[3 * j + 0] * dNdxi[3 * a + 0] + Jinv[3 * j + 1] * dNdxi[3 * a + 1] + Jinv[3 * j + 2] * dNdxi[3 * a + 2];
  if (incompatible) {
    s = detJ0 / *detJ;
    for (k = 0; k < 3; k++)
      for (j = 0; j < 3; j++) G[3 * (8 + k) + j] = J0inv[3 * j + k] * (-2 * q[k]) * s;
  }
  PetscFunctionReturn(0);
}

/* Inverse Jacobian and determinant at the element centre (needed by the bubble modes). */
static PetscErrorCode Hex8CentreJacobian(const PetscReal X[24], PetscReal J0inv[9], PetscReal *detJ0)
{
  const PetscReal q[3] = {0, 0, 0};
  PetscReal       N[8], dNdxi[24];

  PetscFunctionBeginUser;
  PetscCall(Hex8Shape(q, N, dNdxi));
  PetscCall(Hex8Jacobian(X, dNdxi, -1, J0inv, detJ0));
  PetscFunctionReturn(0);
}

/* Stiffness over nodes + (if incompatible) bubble dofs 24 + 3k + d, row-major with leading
   dimension HEX8_LDX. Isotropic block form K_ab,ij = lambda Ga_i Gb_j + mu Ga_j Gb_i +
   mu delta_ij Ga.Gb avoids forming B and D; upper triangle computed, then mirrored so that
   the result is exactly symmetric. */
static PetscErrorCode Hex8StiffnessExtended(const PetscReal X[24], PetscReal lambda, PetscReal mu, PetscBool incompatible, PetscReal Kx[HEX8_LDX * HEX8_LDX])
{
  const PetscInt nn = incompatible ? HEX8_NX : 8, n = 3 * nn;
  PetscReal      J0inv[9] = {0}, detJ0 = 0, N[8], G[3 * HEX8_NX], detJ;
  PetscInt       gp, a, b, i, j, r, c;

  PetscFunctionBeginUser;
  for (r = 0; r < n; r++)
    for (c = 0; c < n; c++) Kx[r * HEX8_LDX + c] = 0;
  if (incompatible) PetscCall(Hex8CentreJacobian(X, J0inv, &detJ0));
  for (gp = 0; gp < 8; gp++) {
    PetscCall(Hex8Gradients(X, gp, incompatible, J0inv, detJ0, N, G, &detJ));
    for (a = 0; a < nn; a++) {
      const PetscReal *Ga = &G[3 * a];

      for (b = a; b < nn; b++) {
        const PetscReal *Gb = &G[3 * b];
        const PetscReal  md = mu * detJ * (Ga[0] * Gb[0] + Ga[1] * Gb[1] + Ga[2] * Gb[2]);

        for (i = 0; i < 3; i++) {
          PetscReal *row = &Kx[(3 * a + i) * HEX8_LDX + 3 * b];

          for (j = 0; j < 3; j++) row[j] += detJ * (lambda * Ga[i] * Gb[j] + mu * Ga[j] * Gb[i]);
          row[i] += md;
        }
      }
    }
  }
  for (r = 0; r < n; r++)
    for (c = r + 1; c < n; c++) Kx[c * HEX8_LDX + r] = Kx[r * HEX8_LDX + c];
  PetscFunctionReturn(0);
}

/* Xc = Kaa^{-1} Kau (9 x 24, column-major, leading dimension 9) by Cholesky: Kaa is SPD for a
   valid element, so a failed factorisation means a broken element or material. */
static PetscErrorCode Hex8CondensationSolve(const PetscReal Kx[HEX8_LDX * HEX8_LDX], PetscReal Xc[9 * 24])
{
  PetscReal    Kaa[81];
  PetscBLASInt n = 9, nrhs = 24, info = 0;
  PetscInt     k, l, j;

  PetscFunctionBeginUser;
  for (k = 0; k < 9; k++) {
    for (l = 0; l < 9; l++) Kaa[k + 9 * l] = Kx[(24 + k) * HEX8_LDX + 24 + l];
    for (j = 0; j < 24; j++) Xc[k + 9 * j] = Kx[(24 + k) * HEX8_LDX + j];
  }
  PetscCallBLAS("LAPACKpotrf", LAPACKpotrf_("L", &n, Kaa, &n, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Hex8: incompatible-mode matrix not positive definite (potrf info %d)", (int)info);
  PetscCallBLAS("LAPACKpotrs", LAPACKpotrs_("L", &n, &nrhs, Kaa, &n, Xc, &n, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Hex8: potrs failed with info %d", (int)info);
  PetscFunctionReturn(0);
}

PetscErrorCode Hex8Stiffness(const PetscReal X[24], PetscReal E, PetscReal nu, Hex8Formulation form, PetscReal Ke[576])
{
  PetscReal       Kx[HEX8_LDX * HEX8_LDX], Xc[9 * 24], lambda, mu;
  const PetscBool incompatible = (PetscBool)(form == HEX8_INCOMPATIBLE);
  PetscInt        i, j, k;

  PetscFunctionBeginUser;
  PetscCheck(form == HEX8_FULL || form == HEX8_INCOMPATIBLE, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Unknown Hex8Formulation %d", (int)form);
  PetscCall(LameConstants(E, nu, &lambda, &mu));
  PetscCall(Hex8StiffnessExtended(X, lambda, mu, incompatible, Kx));
  if (!incompatible) {
    for (i = 0; i < 24; i++)
      for (j = 0; j < 24; j++) Ke[24 * i + j] = Kx[i * HEX8_LDX + j];
    PetscFunctionReturn(0);
  }
  /* Static condensation K = Kuu - Kua Kaa^{-1} Kau; upper triangle, mirrored for exact symmetry */
  PetscCall(Hex8CondensationSolve(Kx, Xc));
  for (i = 0; i < 24; i++) {
    const PetscReal *Kua = &Kx[i * HEX8_LDX + 24];

    for (j = i; j < 24; j++) {
      const PetscReal *x = &Xc[9 * j];
      PetscReal        s = 0;

      for (k = 0; k < 9; k++) s += Kua[k] * x[k];
      Ke[24 * i + j] = Kx[i * HEX8_LDX + j] - s;
      Ke[24 * j + i] = Ke[24 * i + j];
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Hex8Mass(const PetscReal X[24], PetscReal rho, PetscReal Me[576])
{
  PetscReal m[64] = {0}, N[8], G[3 * HEX8_NX], detJ, J0inv[9] = {0};
  PetscInt  gp, a, b, d;

  PetscFunctionBeginUser;
  for (gp = 0; gp < 8; gp++) {
    PetscCall(Hex8Gradients(X, gp, PETSC_FALSE, J0inv, 0, N, G, &detJ));
    for (a = 0; a < 8; a++)
      for (b = a; b < 8; b++) m[8 * a + b] += rho * detJ * N[a] * N[b];
  }
  for (a = 0; a < 576; a++) Me[a] = 0;
  for (a = 0; a < 8; a++)
    for (b = a; b < 8; b++)
      for (d = 0; d < 3; d++) {
        Me[24 * (3 * a + d) + 3 * b + d] = m[8 * a + b];
        Me[24 * (3 * b + d) + 3 * a + d] = m[8 * a + b];
      }
  PetscFunctionReturn(0);
}

PetscErrorCode Hex8Volume(const PetscReal X[24], PetscReal *volume)
{
  PetscReal N[8], G[3 * HEX8_NX], detJ, J0inv[9] = {0}, v = 0;
  PetscInt  gp;

  PetscFunctionBeginUser;
  for (gp = 0; gp < 8; gp++) {
    PetscCall(Hex8Gradients(X, gp, PETSC_FALSE, J0inv, 0, N, G, &detJ));
    v += detJ;
  }
  *volume = v;
  PetscFunctionReturn(0);
}

PetscErrorCode Hex8Stress(const PetscReal X[24], const PetscReal u[24], PetscReal E, PetscReal nu, Hex8Formulation form, PetscReal sigma[48])
{
  PetscReal       D[36], Kx[HEX8_LDX * HEX8_LDX], Xc[9 * 24], alpha[9] = {0}, J0inv[9] = {0}, detJ0 = 0;
  PetscReal       N[8], G[3 * HEX8_NX], detJ, H[9], eps[6], lambda, mu;
  const PetscBool incompatible = (PetscBool)(form == HEX8_INCOMPATIBLE);
  PetscInt        gp, a, i, j, k;

  PetscFunctionBeginUser;
  PetscCheck(form == HEX8_FULL || form == HEX8_INCOMPATIBLE, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Unknown Hex8Formulation %d", (int)form);
  PetscCall(ElasticityVoigt(E, nu, D));
  if (incompatible) {
    /* Internal modes from the condensation: alpha = -Kaa^{-1} Kau u */
    PetscCall(LameConstants(E, nu, &lambda, &mu));
    PetscCall(Hex8StiffnessExtended(X, lambda, mu, PETSC_TRUE, Kx));
    PetscCall(Hex8CondensationSolve(Kx, Xc));
    for (j = 0; j < 24; j++)
      for (k = 0; k < 9; k++) alpha[k] -= Xc[k + 9 * j] * u[j];
    PetscCall(Hex8CentreJacobian(X, J0inv, &detJ0));
  }
  for (gp = 0; gp < 8; gp++) {
    PetscCall(Hex8Gradients(X, gp, incompatible, J0inv, detJ0, N, G, &detJ));
    /* H[3i+j] = du_i/dx_j */
    for (i = 0; i < 9; i++) H[i] = 0;
    for (a = 0; a < 8; a++)
      for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) H[3 * i + j] += u[3 * a + i] * G[3 * a + j];
    if (incompatible)
      for (k = 0; k < 3; k++)
        for (i = 0; i < 3; i++)
          for (j = 0; j < 3; j++) H[3 * i + j] += alpha[3 * k + i] * G[3 * (8 + k) + j];
    eps[0] = H[0];
    eps[1] = H[4];
    eps[2] = H[8];
    eps[3] = H[5] + H[7];
    eps[4] = H[2] + H[6];
    eps[5] = H[1] + H[3];
    for (i = 0; i < 6; i++) {
      PetscReal s = 0;

      for (j = 0; j < 6; j++) s += D[6 * i + j] * eps[j];
      sigma[6 * gp + i] = s;
    }
  }
  PetscFunctionReturn(0);
}

/* Bilinear quad at Gauss point gp: shape functions, t1 x t2 (tangents along s and t) and
   |t1| |t2| (to detect a degenerate face). */
static PetscErrorCode QuadAt(const PetscReal X[12], PetscReal s, PetscReal t, PetscReal N[4], PetscReal c[3], PetscReal *scale)
{
  PetscReal t1[3] = {0}, t2[3] = {0};
  PetscInt        a, d;

  PetscFunctionBeginUser;
  for (a = 0; a < 4; a++) {
    const PetscReal fs = 1 + quadNode[a][0] * s, ft = 1 + quadNode[a][1] * t;

    N[a] = 0.25 * fs * ft;
    for (d = 0; d < 3; d++) {
      t1[d] += 0.25 * quadNode[a][0] * ft * X[3 * a + d];
      t2[d] += 0.25 * quadNode[a][1] * fs * X[3 * a + d];
    }
  }
  c[0] = t1[1] * t2[2] - t1[2] * t2[1];
  c[1] = t1[2] * t2[0] - t1[0] * t2[2];
  c[2] = t1[0] * t2[1] - t1[1] * t2[0];
  *scale = PetscSqrtReal((t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]) * (t2[0] * t2[0] + t2[1] * t2[1] + t2[2] * t2[2]));
  PetscFunctionReturn(0);
}

static PetscErrorCode QuadGauss(const PetscReal X[12], PetscInt gp, PetscReal N[4], PetscReal c[3], PetscReal *scale)
{
  PetscFunctionBeginUser;
  PetscCall(QuadAt(X, GAUSS_PT * quadNode[gp][0], GAUSS_PT * quadNode[gp][1], N, c, scale));
  PetscFunctionReturn(0);
}

PetscErrorCode QuadArea(const PetscReal X[12], PetscReal *area)
{
  PetscReal N[4], c[3], scale, A = 0;
  PetscInt  gp;

  PetscFunctionBeginUser;
  for (gp = 0; gp < 4; gp++) {
    PetscCall(QuadGauss(X, gp, N, c, &scale));
    A += PetscSqrtReal(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  }
  *area = A;
  PetscFunctionReturn(0);
}

PetscErrorCode QuadPairPenaltyStiffness(const PetscReal Xa[12], PetscReal epsN, PetscReal epsT, PetscReal Kc[576])
{
  const PetscBool all[4] = {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE};

  PetscFunctionBeginUser;
  PetscCall(QuadPairPenaltyStiffnessActive(Xa, epsN, epsT, all, Kc));
  PetscFunctionReturn(0);
}

PetscErrorCode QuadGaussPoints(const PetscReal Xa[12], PetscReal N[16], PetscReal w[4], PetscReal n[12])
{
  PetscReal c[3], scale, dA;

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4; gp++) {
    PetscCall(QuadGauss(Xa, gp, &N[4 * gp], c, &scale));
    dA = PetscSqrtReal(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    PetscCheck(dA > HEX8_DEGENERATE * scale, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Quad face degenerate at Gauss point %" PetscInt_FMT ": |t1 x t2| = %g, no normal", gp, (double)dA);
    w[gp] = dA;
    for (PetscInt k = 0; k < 3; k++) n[3 * gp + k] = c[k] / dA;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode QuadPairPenaltyStiffnessActive(const PetscReal Xa[12], PetscReal epsN, PetscReal epsT, const PetscBool active[4], PetscReal Kc[576])
{
  PetscReal M[144] = {0}, N[4], c[3], n[3], P[9], dA, scale;
  PetscInt  gp, a, b, k, l;

  PetscFunctionBeginUser;
  PetscCheck(epsN >= 0 && epsT >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Penalty parameters must be non-negative: epsN = %g, epsT = %g", (double)epsN, (double)epsT);
  for (gp = 0; gp < 4; gp++) {
    if (!active[gp]) continue;
    PetscCall(QuadGauss(Xa, gp, N, c, &scale));
    dA = PetscSqrtReal(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    PetscCheck(dA > HEX8_DEGENERATE * scale, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Quad face degenerate at Gauss point %" PetscInt_FMT ": |t1 x t2| = %g, no normal", gp, (double)dA);
    for (k = 0; k < 3; k++) n[k] = c[k] / dA;
    /* P = epsN n n' + epsT (I - n n') */
    for (k = 0; k < 3; k++)
      for (l = 0; l < 3; l++) P[3 * k + l] = (epsN - epsT) * n[k] * n[l] + (k == l ? epsT : 0);
    /* M = int N' P N dA on one face (12x12); upper node blocks only, mirrored below */
    for (a = 0; a < 4; a++)
      for (b = a; b < 4; b++) {
        const PetscReal w = N[a] * N[b] * dA;

        for (k = 0; k < 3; k++)
          for (l = 0; l < 3; l++) M[12 * (3 * a + k) + 3 * b + l] += w * P[3 * k + l];
      }
  }
  for (a = 0; a < 12; a++)
    for (b = a + 1; b < 12; b++) M[12 * b + a] = M[12 * a + b];
  /* B = [-N, N]: Kc = [M -M; -M M] */
  for (a = 0; a < 12; a++)
    for (b = 0; b < 12; b++) {
      Kc[24 * a + b]             = M[12 * a + b];
      Kc[24 * a + b + 12]        = -M[12 * a + b];
      Kc[24 * (a + 12) + b]      = -M[12 * a + b];
      Kc[24 * (a + 12) + b + 12] = M[12 * a + b];
    }
  PetscFunctionReturn(0);
}

PetscErrorCode QuadNodalPoints(const PetscReal Xa[12], PetscReal N[16], PetscReal w[4], PetscReal n[12])
{
  PetscReal c[3], scale, dA;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < 4; a++) {
    /* the trapezoidal rule in each direction: weight 1 at each corner of [-1,1]^2 */
    PetscCall(QuadAt(Xa, quadNode[a][0], quadNode[a][1], &N[4 * a], c, &scale));
    dA = PetscSqrtReal(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    PetscCheck(dA > HEX8_DEGENERATE * scale, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Quad face degenerate at node %" PetscInt_FMT ": |t1 x t2| = %g, no normal", a, (double)dA);
    w[a] = dA;
    for (PetscInt k = 0; k < 3; k++) n[3 * a + k] = c[k] / dA;
    for (PetscInt b = 0; b < 4; b++) N[4 * a + b] = a == b ? 1.0 : 0.0; /* exact at the nodes */
  }
  PetscFunctionReturn(0);
}

PetscErrorCode QuadPairPenaltyStiffnessPoints(const PetscReal N[16], const PetscReal w[4], const PetscReal n[12], PetscReal epsN, PetscReal epsT, const PetscBool active[4], const PetscBool released[4], const PetscReal slipDir[16], PetscReal Kc[576])
{
  PetscReal M[144] = {0}, P[9];

  PetscFunctionBeginUser;
  PetscCheck(epsN >= 0 && epsT >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Penalty parameters must be non-negative: epsN = %g, epsT = %g", (double)epsN, (double)epsT);
  for (PetscInt q = 0; q < 4; q++) {
    const PetscReal *nq = &n[3 * q], *Nq = &N[4 * q];
    const PetscReal et = (released && released[q]) ? 0 : epsT;
    if (!active[q]) continue;
    for (PetscInt k = 0; k < 3; k++)
      for (PetscInt l = 0; l < 3; l++) P[3 * k + l] = (epsN - et) * nq[k] * nq[l] + (k == l ? et : 0);
    if (released && released[q] && slipDir) { /* a pair slipping by friction along d: stiffness slipDir[3] across d */
      const PetscReal *d = &slipDir[4 * q], ka = slipDir[4 * q + 3];
      for (PetscInt k = 0; k < 3; k++)
        for (PetscInt l = 0; l < 3; l++) P[3 * k + l] += ka * ((k == l ? 1 : 0) - nq[k] * nq[l] - d[k] * d[l]);
    }
    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt b = 0; b < 4; b++) {
        const PetscReal f = Nq[a] * Nq[b] * w[q];
        if (f == 0) continue;
        for (PetscInt k = 0; k < 3; k++)
          for (PetscInt l = 0; l < 3; l++) M[12 * (3 * a + k) + 3 * b + l] += f * P[3 * k + l];
      }
  }
  for (PetscInt a = 0; a < 12; a++)
    for (PetscInt b = 0; b < 12; b++) {
      Kc[24 * a + b]             = M[12 * a + b];
      Kc[24 * a + b + 12]        = -M[12 * a + b];
      Kc[24 * (a + 12) + b]      = -M[12 * a + b];
      Kc[24 * (a + 12) + b + 12] = M[12 * a + b];
    }
  PetscFunctionReturn(0);
}
