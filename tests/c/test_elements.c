static char help[] = "Verification of the element kernels (boltrom_element.h): symmetry, rigid modes, mass,\n"
                     "patch test on a distorted 2x2x2 block, bending/locking, quad penalty, inverted elements.\n"
                     "Prints PASS/FAIL name value per check; exits non-zero if any check fails.\n";

#include <boltrom_element.h> /* petscsys.h must precede petscblaslapack.h */
#include <petscblaslapack.h>

/* Distorted hexahedron: a 2 x 1.5 x 1.2 box with every node moved (all det J > 0) */
static const PetscReal distortedHex[24] = {0.10, -0.05, 0.08, 1.88, 0.07, -0.04, 2.06, 1.60, 1.11, -0.03, 1.39, 1.25,
                                           0.09, 0.04,  1.10, 1.93, -0.08, 1.32, 2.11, 1.44, 1.23, -0.05, 1.59, 1.13};
static const PetscReal hexRef[8][3] = {
  {-1, -1, -1},
  {1,  -1, -1},
  {1,  1,  -1},
  {-1, 1,  -1},
  {-1, -1, 1 },
  {1,  -1, 1 },
  {1,  1,  1 },
  {-1, 1,  1 }
};

static PetscErrorCode Report(const char *name, PetscReal value, PetscBool ok, PetscInt *nfail)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %s %.6e\n", ok ? "PASS" : "FAIL", name, (double)value));
  if (!ok) (*nfail)++;
  PetscFunctionReturn(0);
}

/* value < tol, written so that NaN fails */
static PetscErrorCode CheckBelow(const char *name, PetscReal value, PetscReal tol, PetscInt *nfail)
{
  PetscFunctionBeginUser;
  PetscCall(Report(name, value, (PetscBool)(value < tol), nfail));
  PetscFunctionReturn(0);
}

static PetscErrorCode SymmetryError(PetscInt n, const PetscReal *K, PetscReal *err)
{
  PetscReal d = 0, m = 0;
  PetscInt  i, j;

  PetscFunctionBeginUser;
  for (i = 0; i < n; i++)
    for (j = 0; j < n; j++) {
      d = PetscMax(d, PetscAbsReal(K[n * i + j] - K[n * j + i]));
      m = PetscMax(m, PetscAbsReal(K[n * i + j]));
    }
  *err = d / m;
  PetscFunctionReturn(0);
}

static PetscErrorCode FrobeniusNorm(PetscInt m, PetscInt n, const PetscReal *A, PetscReal *nrm)
{
  PetscReal s = 0;
  PetscInt  i;

  PetscFunctionBeginUser;
  for (i = 0; i < m * n; i++) s += A[i] * A[i];
  *nrm = PetscSqrtReal(s);
  PetscFunctionReturn(0);
}

/* y = A x, A m x n row-major */
static PetscErrorCode MatVec(PetscInt m, PetscInt n, const PetscReal *A, const PetscReal *x, PetscReal *y)
{
  PetscInt i, j;

  PetscFunctionBeginUser;
  for (i = 0; i < m; i++) {
    y[i] = 0;
    for (j = 0; j < n; j++) y[i] += A[n * i + j] * x[j];
  }
  PetscFunctionReturn(0);
}

/* Eigenvalues (ascending) of a symmetric n x n matrix, n <= 24 */
static PetscErrorCode SymEig(PetscInt n, const PetscReal *A, PetscReal *w)
{
  PetscReal    a[576], work[24 * 24];
  PetscBLASInt bn, lwork = 24 * 24, info;
  PetscInt     i;

  PetscFunctionBeginUser;
  PetscCheck(n <= 24, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SymEig: n = %" PetscInt_FMT " > 24", n);
  PetscCall(PetscBLASIntCast(n, &bn));
  for (i = 0; i < n * n; i++) a[i] = A[i];
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("N", "U", &bn, a, &bn, w, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "dsyev failed: info %d", (int)info);
  PetscFunctionReturn(0);
}

/* Symmetric positive definite solve A x = b in place (A destroyed), column/row-major alike */
static PetscErrorCode SPDSolve(PetscInt n, PetscReal *A, PetscReal *b)
{
  PetscBLASInt bn, one = 1, info;

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCallBLAS("LAPACKpotrf", LAPACKpotrf_("L", &bn, A, &bn, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "dpotrf failed: info %d", (int)info);
  PetscCallBLAS("LAPACKpotrs", LAPACKpotrs_("L", &bn, &one, A, &bn, b, &bn, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "dpotrs failed: info %d", (int)info);
  PetscFunctionReturn(0);
}

/* Rigid motion m (0-2 translations, 3-5 rotations about the axes through c) at points X */
static PetscErrorCode RigidMode(PetscInt m, PetscInt npts, const PetscReal *X, const PetscReal c[3], PetscReal *r)
{
  PetscInt a, d;

  PetscFunctionBeginUser;
  for (a = 0; a < npts; a++) {
    const PetscReal x[3] = {X[3 * a] - c[0], X[3 * a + 1] - c[1], X[3 * a + 2] - c[2]};

    for (d = 0; d < 3; d++) r[3 * a + d] = 0;
    if (m < 3) r[3 * a + m] = 1;
    else {
      const PetscInt k = m - 3; /* u = e_k x x */

      r[3 * a + (k + 1) % 3] = -x[(k + 2) % 3];
      r[3 * a + (k + 2) % 3] = x[(k + 1) % 3];
    }
  }
  PetscFunctionReturn(0);
}

/* Checks 1-2: symmetry, rigid modes and rank of the stiffness */
static PetscErrorCode CheckStiffnessBasics(Hex8Formulation form, const char *tag, PetscInt *nfail)
{
  PetscReal K[576], r[24], Kr[24], w[24], err, nK, nr, nKr, worst = 0, c[3] = {1, 0.75, 0.6};
  PetscInt  m, i, rank = 0;
  char      name[64];

  PetscFunctionBeginUser;
  PetscCall(Hex8Stiffness(distortedHex, 210e3, 0.3, form, K));
  PetscCall(SymmetryError(24, K, &err));
  PetscCall(PetscSNPrintf(name, sizeof(name), "symmetry_Ke_%s", tag));
  PetscCall(CheckBelow(name, err, 1e-14, nfail));

  PetscCall(FrobeniusNorm(24, 24, K, &nK));
  for (m = 0; m < 6; m++) {
    PetscCall(RigidMode(m, 8, distortedHex, c, r));
    PetscCall(MatVec(24, 24, K, r, Kr));
    PetscCall(FrobeniusNorm(24, 1, r, &nr));
    PetscCall(FrobeniusNorm(24, 1, Kr, &nKr));
    worst = PetscMax(worst, nKr / (nK * nr));
  }
  PetscCall(PetscSNPrintf(name, sizeof(name), "rigid_modes_Ke_%s", tag));
  PetscCall(CheckBelow(name, worst, 1e-12, nfail));

  PetscCall(SymEig(24, K, w));
  for (i = 0; i < 24; i++)
    if (w[i] > 1e-8 * w[23]) rank++;
  PetscCall(PetscSNPrintf(name, sizeof(name), "rank_Ke_%s", tag));
  PetscCall(Report(name, (PetscReal)rank, (PetscBool)(rank == 18), nfail));
  /* the 6 smallest eigenvalues are zero (relative), none negative */
  worst = 0;
  for (i = 0; i < 6; i++) worst = PetscMax(worst, PetscAbsReal(w[i]) / w[23]);
  PetscCall(PetscSNPrintf(name, sizeof(name), "zero_eigs_Ke_%s", tag));
  PetscCall(CheckBelow(name, worst, 1e-12, nfail));
  PetscCall(PetscSNPrintf(name, sizeof(name), "min_nonzero_eig_Ke_%s", tag));
  PetscCall(Report(name, w[6] / w[23], (PetscBool)(w[6] / w[23] > 1e-6), nfail));
  PetscFunctionReturn(0);
}

/* Checks 1 and 3: mass symmetry, positive definiteness, total mass, parallelepiped volume */
static PetscErrorCode CheckMassVolume(PetscInt *nfail)
{
  const PetscReal rho = 7850, O[3] = {0.3, -0.2, 0.1};
  const PetscReal e[3][3] = {
    {1.5, 0.2,  0.1 },
    {0.4, 1.1,  -0.2},
    {0.3, 0.25, 0.9 }
  };
  PetscReal M[576], w[24], X[24], V, Vex, err, s;
  PetscInt  a, b, d, k;
  char      name[64];

  PetscFunctionBeginUser;
  PetscCall(Hex8Mass(distortedHex, rho, M));
  PetscCall(SymmetryError(24, M, &err));
  PetscCall(CheckBelow("symmetry_Me", err, 1e-14, nfail));
  PetscCall(SymEig(24, M, w));
  PetscCall(Report("posdef_Me_min_eig_ratio", w[0] / w[23], (PetscBool)(w[0] / w[23] > 1e-3), nfail));
  PetscCall(Hex8Volume(distortedHex, &V));
  for (d = 0; d < 3; d++) {
    s = 0;
    for (a = 0; a < 8; a++)
      for (b = 0; b < 8; b++) s += M[24 * (3 * a + d) + 3 * b + d];
    PetscCall(PetscSNPrintf(name, sizeof(name), "mass_sum_dir%" PetscInt_FMT, d));
    PetscCall(CheckBelow(name, PetscAbsReal(s - rho * V) / (rho * V), 1e-14, nfail));
  }
  /* off-direction blocks carry no mass */
  s = 0;
  for (a = 0; a < 24; a++)
    for (b = 0; b < 24; b++)
      if (a % 3 != b % 3) s = PetscMax(s, PetscAbsReal(M[24 * a + b]));
  PetscCall(CheckBelow("mass_cross_direction_zero", s, 1e-300, nfail));

  /* skewed parallelepiped: volume = |det(e1, e2, e3)| */
  for (a = 0; a < 8; a++)
    for (d = 0; d < 3; d++) {
      X[3 * a + d] = O[d];
      for (k = 0; k < 3; k++) X[3 * a + d] += 0.5 * (1 + hexRef[a][k]) * e[k][d];
    }
  Vex = PetscAbsReal(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]));
  PetscCall(Hex8Volume(X, &V));
  PetscCall(CheckBelow("volume_parallelepiped", PetscAbsReal(V - Vex) / Vex, 1e-14, nfail));
  PetscFunctionReturn(0);
}

/* Check 4: patch test, 2x2x2 distorted elements in the unit cube, interior node free */
static PetscErrorCode CheckPatch(Hex8Formulation form, const char *tag, PetscInt *nfail)
{
  const PetscReal E = 210e3, nu = 0.3;
  const PetscReal A[3][3] = {
    {0.10,  0.20,  -0.15},
    {0.07,  -0.20, 0.11 },
    {-0.09, 0.13,  0.25 }
  };
  const PetscReal b[3] = {0.01, -0.02, 0.03};
  /* moved nodes (id = i + 3j + 9k): interior ~20% of the element size, face nodes within their
     face, edge nodes along their edge; corners fixed */
  const PetscInt  nmove            = 11;
  const PetscInt  moved[11]        = {13, 1, 4, 10, 12, 14, 16, 22, 9, 23, 3};
  const PetscReal newpos[11][3]    = {
    {0.61, 0.42, 0.57},
    {0.56, 0,    0   },
    {0.58, 0.44, 0   },
    {0.53, 0,    0.42},
    {0,    0.55, 0.43},
    {1,    0.45, 0.60},
    {0.43, 1,    0.55},
    {0.45, 0.57, 1   },
    {0,    0,    0.45},
    {1,    0.56, 1   },
    {0,    0.47, 0   }
  };
  PetscReal       coord[81], u[81], K[81 * 81], Ke[576], Xe[24], ue[24], sig[48], D[36], epsA[6], sigA[6];
  PetscReal       Kii[9], rhs[3], err, smax, vol, Vsum = 0;
  PetscBLASInt    three = 3, one = 1, ipiv[3], info;
  PetscInt        i, j, k, e, a, d, n, r, c, conn[8];

  PetscFunctionBeginUser;
  for (k = 0; k < 3; k++)
    for (j = 0; j < 3; j++)
      for (i = 0; i < 3; i++) {
        n                = i + 3 * j + 9 * k;
        coord[3 * n + 0] = 0.5 * i;
        coord[3 * n + 1] = 0.5 * j;
        coord[3 * n + 2] = 0.5 * k;
      }
  for (i = 0; i < nmove; i++)
    for (d = 0; d < 3; d++) coord[3 * moved[i] + d] = newpos[i][d];
  for (n = 0; n < 27; n++)
    for (d = 0; d < 3; d++) u[3 * n + d] = b[d] + A[d][0] * coord[3 * n] + A[d][1] * coord[3 * n + 1] + A[d][2] * coord[3 * n + 2];

  /* assemble */
  for (i = 0; i < 81 * 81; i++) K[i] = 0;
  for (e = 0; e < 8; e++) {
    const PetscInt ei = e % 2, ej = (e / 2) % 2, ek = e / 4;

    for (a = 0; a < 8; a++) {
      conn[a] = (ei + (hexRef[a][0] > 0)) + 3 * (ej + (hexRef[a][1] > 0)) + 9 * (ek + (hexRef[a][2] > 0));
      for (d = 0; d < 3; d++) Xe[3 * a + d] = coord[3 * conn[a] + d];
    }
    PetscCall(Hex8Volume(Xe, &vol));
    Vsum += vol;
    PetscCall(Hex8Stiffness(Xe, E, nu, form, Ke));
    for (r = 0; r < 24; r++)
      for (c = 0; c < 24; c++) K[81 * (3 * conn[r / 3] + r % 3) + 3 * conn[c / 3] + c % 3] += Ke[24 * r + c];
  }
  if (form == HEX8_FULL) PetscCall(CheckBelow("patch_volume_sum", PetscAbsReal(Vsum - 1), 1e-14, nfail));

  /* interior node 13 (dofs 39-41): K_II u_I = -K_IB u_B */
  for (r = 0; r < 3; r++) {
    rhs[r] = 0;
    for (c = 0; c < 81; c++)
      if (c < 39 || c > 41) rhs[r] -= K[81 * (39 + r) + c] * u[c];
    for (c = 0; c < 3; c++) Kii[r + 3 * c] = K[81 * (39 + r) + 39 + c];
  }
  PetscCallBLAS("LAPACKgesv", LAPACKgesv_(&three, &one, Kii, &three, ipiv, rhs, &three, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "dgesv failed: info %d", (int)info);
  err = PetscSqrtReal(PetscSqr(rhs[0] - u[39]) + PetscSqr(rhs[1] - u[40]) + PetscSqr(rhs[2] - u[41])) / PetscSqrtReal(PetscSqr(u[39]) + PetscSqr(u[40]) + PetscSqr(u[41]));
  {
    char name[64];

    PetscCall(PetscSNPrintf(name, sizeof(name), "patch_interior_disp_%s", tag));
    PetscCall(CheckBelow(name, err, 1e-10, nfail));
  }
  for (d = 0; d < 3; d++) u[39 + d] = rhs[d];

  /* stresses at all Gauss points vs D eps(A) */
  PetscCall(ElasticityVoigt(E, nu, D));
  epsA[0] = A[0][0];
  epsA[1] = A[1][1];
  epsA[2] = A[2][2];
  epsA[3] = A[1][2] + A[2][1];
  epsA[4] = A[0][2] + A[2][0];
  epsA[5] = A[0][1] + A[1][0];
  PetscCall(MatVec(6, 6, D, epsA, sigA));
  smax = 0;
  for (i = 0; i < 6; i++) smax = PetscMax(smax, PetscAbsReal(sigA[i]));
  err = 0;
  for (e = 0; e < 8; e++) {
    const PetscInt ei = e % 2, ej = (e / 2) % 2, ek = e / 4;

    for (a = 0; a < 8; a++) {
      conn[a] = (ei + (hexRef[a][0] > 0)) + 3 * (ej + (hexRef[a][1] > 0)) + 9 * (ek + (hexRef[a][2] > 0));
      for (d = 0; d < 3; d++) {
        Xe[3 * a + d] = coord[3 * conn[a] + d];
        ue[3 * a + d] = u[3 * conn[a] + d];
      }
    }
    PetscCall(Hex8Stress(Xe, ue, E, nu, form, sig));
    for (i = 0; i < 48; i++) err = PetscMax(err, PetscAbsReal(sig[i] - sigA[i % 6]) / smax);
  }
  {
    char name[64];

    PetscCall(PetscSNPrintf(name, sizeof(name), "patch_stress_%s", tag));
    PetscCall(CheckBelow(name, err, 1e-10, nfail));
  }
  PetscFunctionReturn(0);
}

/* Check 5a: one a x b x c element (aspect 4) with the nodal values of exact pure bending
   (uniaxial stress, lateral faces free): returns U_h / U_exact and the Gauss-point stress
   error relative to max |sigma_xx| (exact: sigma_xx = -E kappa z, all else zero; Gauss point g
   lies in the octant of node g). */
static PetscErrorCode BendingElement(Hex8Formulation form, PetscReal *ratio, PetscReal *stressErr)
{
  const PetscReal a = 4, b = 1, c = 1, E = 1000, nu = 0.3, kappa = 0.01;
  PetscReal       X[24], u[24], K[576], Ku[24], sig[48], U = 0, Uex, smax, zg;
  PetscInt        n, i;

  PetscFunctionBeginUser;
  for (n = 0; n < 8; n++) {
    const PetscReal x = 0.5 * a * hexRef[n][0], y = 0.5 * b * hexRef[n][1], z = 0.5 * c * hexRef[n][2];

    X[3 * n + 0] = x;
    X[3 * n + 1] = y;
    X[3 * n + 2] = z;
    u[3 * n + 0] = -kappa * x * z;
    u[3 * n + 1] = nu * kappa * y * z;
    u[3 * n + 2] = 0.5 * kappa * (x * x + nu * (z * z - y * y));
  }
  PetscCall(Hex8Stiffness(X, E, nu, form, K));
  PetscCall(MatVec(24, 24, K, u, Ku));
  for (i = 0; i < 24; i++) U += 0.5 * u[i] * Ku[i];
  Uex    = 0.5 * E * kappa * kappa * (b * c * c * c / 12) * a;
  *ratio = U / Uex;
  PetscCall(Hex8Stress(X, u, E, nu, form, sig));
  smax       = E * kappa * 0.5 * c / PetscSqrtReal(3);
  *stressErr = 0;
  for (n = 0; n < 8; n++) {
    zg = 0.5 * c * hexRef[n][2] / PetscSqrtReal(3);
    for (i = 0; i < 6; i++) *stressErr = PetscMax(*stressErr, PetscAbsReal(sig[6 * n + i] - (i == 0 ? -E * kappa * zg : 0)) / smax);
  }
  PetscFunctionReturn(0);
}

/* Check 5b: cantilever 10 x 1 x 1 elements (L = 10, h = b = 1), clamped at x = 0, end moment M
   as a couple of x-forces at the tip nodes, nu = 0. Returns tip deflection and rotation. */
static PetscErrorCode Cantilever(Hex8Formulation form, PetscReal *wmin, PetscReal *wmax, PetscReal *thmin, PetscReal *thmax)
{
  const PetscInt  nel = 10, nx = nel + 1, nnode = 4 * nx, ndof = 3 * nnode, nfree = ndof - 12;
  const PetscReal E = 1e4, nu = 0, M = 1;
  PetscReal      *K, *Kf, *f, Ke[576], Xe[24];
  PetscInt        e, a, d, r, c, conn[8], n, j;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc3(ndof * ndof, &K, nfree * nfree, &Kf, ndof, &f));
  /* node id = i + nx (j + 2 k), coordinates (i, j, k) */
  for (e = 0; e < nel; e++) {
    for (a = 0; a < 8; a++) {
      const PetscInt i = e + (hexRef[a][0] > 0), jj = hexRef[a][1] > 0, k = hexRef[a][2] > 0;

      conn[a]       = i + nx * (jj + 2 * k);
      Xe[3 * a + 0] = i;
      Xe[3 * a + 1] = jj;
      Xe[3 * a + 2] = k;
    }
    PetscCall(Hex8Stiffness(Xe, E, nu, form, Ke));
    for (r = 0; r < 24; r++)
      for (c = 0; c < 24; c++) K[ndof * (3 * conn[r / 3] + r % 3) + 3 * conn[c / 3] + c % 3] += Ke[24 * r + c];
  }
  /* tip couple: -M/2 on the two top nodes (z = 1), +M/2 on the bottom ones (h = 1) */
  for (j = 0; j < 2; j++) {
    f[3 * (nel + nx * (j + 0)) + 0] = 0.5 * M;
    f[3 * (nel + nx * (j + 2)) + 0] = -0.5 * M;
  }
  /* free dofs: all nodes with i > 0; map dof -> free index */
  {
    PetscInt *map, nf = 0;

    PetscCall(PetscMalloc1(ndof, &map));
    for (n = 0; n < nnode; n++)
      for (d = 0; d < 3; d++) map[3 * n + d] = (n % nx == 0) ? -1 : nf++;
    PetscCheck(nf == nfree, PETSC_COMM_SELF, PETSC_ERR_PLIB, "free dof count %" PetscInt_FMT, nf);
    for (r = 0; r < ndof; r++)
      for (c = 0; c < ndof; c++)
        if (map[r] >= 0 && map[c] >= 0) Kf[nfree * map[r] + map[c]] = K[ndof * r + c];
    for (r = 0; r < ndof; r++)
      if (map[r] >= 0) f[map[r]] = f[r]; /* map[r] <= r: compaction in place is safe */
    PetscCall(SPDSolve(nfree, Kf, f));
    /* scatter back to full numbering (reverse order keeps it in place) */
    for (r = ndof - 1; r >= 0; r--) f[r] = map[r] >= 0 ? f[map[r]] : 0;
    PetscCall(PetscFree(map));
  }
  *wmin = *thmin = PETSC_MAX_REAL;
  *wmax = *thmax = -PETSC_MAX_REAL;
  for (j = 0; j < 2; j++) {
    const PetscInt bot = nel + nx * j, top = nel + nx * (j + 2);
    const PetscReal th = f[3 * bot] - f[3 * top]; /* (u_x(bottom) - u_x(top)) / h */

    *wmin  = PetscMin(*wmin, PetscMin(f[3 * bot + 2], f[3 * top + 2]));
    *wmax  = PetscMax(*wmax, PetscMax(f[3 * bot + 2], f[3 * top + 2]));
    *thmin = PetscMin(*thmin, th);
    *thmax = PetscMax(*thmax, th);
  }
  PetscCall(PetscFree3(K, Kf, f));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckBending(PetscInt *nfail)
{
  const PetscReal L = 10, E = 1e4, Iy = 1.0 / 12, M = 1;
  const PetscReal wex = M * L * L / (2 * E * Iy), thex = M * L / (E * Iy);
  PetscReal       r, serr, wmin, wmax, thmin, thmax, ratio;

  PetscFunctionBeginUser;
  PetscCall(BendingElement(HEX8_INCOMPATIBLE, &r, &serr));
  PetscCall(CheckBelow("bending_energy_incompatible_relerr", PetscAbsReal(r - 1), 1e-10, nfail));
  PetscCall(CheckBelow("bending_stress_incompatible_relerr", serr, 1e-10, nfail));
  PetscCall(BendingElement(HEX8_FULL, &r, &serr));
  PetscCall(Report("bending_energy_full_over_exact_aspect4", r, (PetscBool)(r > 1.05), nfail));

  PetscCall(Cantilever(HEX8_INCOMPATIBLE, &wmin, &wmax, &thmin, &thmax));
  PetscCall(CheckBelow("cantilever_tip_deflection_incompatible_relerr", PetscMax(PetscAbsReal(wmin - wex), PetscAbsReal(wmax - wex)) / wex, 1e-8, nfail));
  PetscCall(CheckBelow("cantilever_tip_rotation_incompatible_relerr", PetscMax(PetscAbsReal(thmin - thex), PetscAbsReal(thmax - thex)) / thex, 1e-8, nfail));
  PetscCall(Cantilever(HEX8_FULL, &wmin, &wmax, &thmin, &thmax));
  ratio = 0.5 * (wmin + wmax) / wex;
  PetscCall(Report("cantilever_tip_deflection_full_over_exact", ratio, (PetscBool)(ratio < 0.95 && ratio > 0), nfail));
  PetscFunctionReturn(0);
}

/* Check 6 on face Xa with unit normal n (expected) and area Aex */
static PetscErrorCode CheckQuad(const PetscReal Xa[12], const PetscReal n[3], PetscReal Aex, const char *tag, PetscInt *nfail)
{
  const PetscReal epsN = 1e3, epsT = 20, g[3] = {0.3, -0.2, 0.5}, c0[3] = {0.2, 0.1, -0.3};
  PetscReal       Kc[576], u[24], f[24], w[24], A, err, nK, nu, nf, gn, Fn, Fa[3] = {0}, Fb[3] = {0}, gt[3], Ft[3], num, den, worst;
  PetscInt        i, d, m, rank = 0;
  char            name[64];

  PetscFunctionBeginUser;
  PetscCall(QuadArea(Xa, &A));
  PetscCall(PetscSNPrintf(name, sizeof(name), "quad_area_%s", tag));
  PetscCall(CheckBelow(name, PetscAbsReal(A - Aex) / Aex, 1e-14, nfail));
  PetscCall(QuadPairPenaltyStiffness(Xa, epsN, epsT, Kc));
  PetscCall(SymmetryError(24, Kc, &err));
  PetscCall(PetscSNPrintf(name, sizeof(name), "quad_symmetry_%s", tag));
  PetscCall(CheckBelow(name, err, 1e-14, nfail));

  /* uniform gap g = u_b - u_a */
  for (i = 0; i < 4; i++)
    for (d = 0; d < 3; d++) {
      u[3 * i + d]      = 0;
      u[12 + 3 * i + d] = g[d];
    }
  PetscCall(MatVec(24, 24, Kc, u, f));
  for (i = 0; i < 4; i++)
    for (d = 0; d < 3; d++) {
      Fa[d] += f[3 * i + d];
      Fb[d] += f[12 + 3 * i + d];
    }
  gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];
  Fn = Fb[0] * n[0] + Fb[1] * n[1] + Fb[2] * n[2];
  PetscCall(PetscSNPrintf(name, sizeof(name), "quad_normal_force_%s", tag));
  PetscCall(CheckBelow(name, PetscAbsReal(Fn - epsN * Aex * gn) / PetscAbsReal(epsN * Aex * gn), 1e-13, nfail));
  num = den = 0;
  for (d = 0; d < 3; d++) {
    gt[d] = g[d] - gn * n[d];
    Ft[d] = Fb[d] - Fn * n[d];
    num += PetscSqr(Ft[d] - epsT * Aex * gt[d]);
    den += PetscSqr(epsT * Aex * gt[d]);
  }
  PetscCall(PetscSNPrintf(name, sizeof(name), "quad_tangential_force_%s", tag));
  PetscCall(CheckBelow(name, PetscSqrtReal(num / den), 1e-12, nfail));
  num = PetscSqrtReal(PetscSqr(Fa[0] + Fb[0]) + PetscSqr(Fa[1] + Fb[1]) + PetscSqr(Fa[2] + Fb[2]));
  den = PetscSqrtReal(PetscSqr(Fb[0]) + PetscSqr(Fb[1]) + PetscSqr(Fb[2]));
  PetscCall(PetscSNPrintf(name, sizeof(name), "quad_action_reaction_%s", tag));
  PetscCall(CheckBelow(name, num / den, 1e-14, nfail));

  /* PSD with rank 12 */
  PetscCall(SymEig(24, Kc, w));
  for (i = 0; i < 24; i++)
    if (w[i] > 1e-10 * w[23]) rank++;
  PetscCall(PetscSNPrintf(name, sizeof(name), "quad_rank_%s", tag));
  PetscCall(Report(name, (PetscReal)rank, (PetscBool)(rank == 12), nfail));
  worst = 0;
  for (i = 0; i < 12; i++) worst = PetscMax(worst, PetscAbsReal(w[i]) / w[23]);
  PetscCall(PetscSNPrintf(name, sizeof(name), "quad_psd_zero_eigs_%s", tag));
  PetscCall(CheckBelow(name, worst, 1e-13, nfail));

  /* same rigid motion on both faces: no force */
  PetscCall(FrobeniusNorm(24, 24, Kc, &nK));
  worst = 0;
  for (m = 0; m < 6; m++) {
    PetscCall(RigidMode(m, 4, Xa, c0, u));
    PetscCall(RigidMode(m, 4, Xa, c0, u + 12));
    PetscCall(MatVec(24, 24, Kc, u, f));
    PetscCall(FrobeniusNorm(24, 1, u, &nu));
    PetscCall(FrobeniusNorm(24, 1, f, &nf));
    worst = PetscMax(worst, nf / (nK * nu));
  }
  PetscCall(PetscSNPrintf(name, sizeof(name), "quad_common_rigid_motion_%s", tag));
  PetscCall(CheckBelow(name, worst, 1e-14, nfail));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckQuads(PetscInt *nfail)
{
  /* square of side 2 in z = 0, ordered like the bottom face (nodes 0-3) of a hex above it:
     t1 x t2 = +z by the right-hand rule */
  const PetscReal sq[12] = {0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0}, ez[3] = {0, 0, 1};
  /* general planar quad, counterclockwise in its plane, then rotated and translated */
  const PetscReal p[4][2] = {
    {0,   0  },
    {2,   0.2},
    {2.4, 1.7},
    {0.3, 1.2}
  };
  const PetscReal ax = 0.7, ay = -0.4, az = 0.3, t[3] = {1, -2, 0.5};
  PetscReal       Rx[9], Ry[9], Rz[9], T[9], R[9], Xq[12], n[3], Aex = 0;
  PetscInt        i, j, k;

  PetscFunctionBeginUser;
  PetscCall(CheckQuad(sq, ez, 4, "square_z0", nfail));

  for (i = 0; i < 4; i++) Aex += 0.5 * (p[i][0] * p[(i + 1) % 4][1] - p[(i + 1) % 4][0] * p[i][1]);
  Rx[0] = 1, Rx[1] = 0, Rx[2] = 0, Rx[3] = 0, Rx[4] = PetscCosReal(ax), Rx[5] = -PetscSinReal(ax), Rx[6] = 0, Rx[7] = PetscSinReal(ax), Rx[8] = PetscCosReal(ax);
  Ry[0] = PetscCosReal(ay), Ry[1] = 0, Ry[2] = PetscSinReal(ay), Ry[3] = 0, Ry[4] = 1, Ry[5] = 0, Ry[6] = -PetscSinReal(ay), Ry[7] = 0, Ry[8] = PetscCosReal(ay);
  Rz[0] = PetscCosReal(az), Rz[1] = -PetscSinReal(az), Rz[2] = 0, Rz[3] = PetscSinReal(az), Rz[4] = PetscCosReal(az), Rz[5] = 0, Rz[6] = 0, Rz[7] = 0, Rz[8] = 1;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) {
      T[3 * i + j] = 0;
      for (k = 0; k < 3; k++) T[3 * i + j] += Rx[3 * i + k] * Ry[3 * k + j];
    }
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) {
      R[3 * i + j] = 0;
      for (k = 0; k < 3; k++) R[3 * i + j] += Rz[3 * i + k] * T[3 * k + j];
    }
  for (i = 0; i < 4; i++)
    for (j = 0; j < 3; j++) Xq[3 * i + j] = t[j] + R[3 * j + 0] * p[i][0] + R[3 * j + 1] * p[i][1];
  for (j = 0; j < 3; j++) n[j] = R[3 * j + 2];
  PetscCall(CheckQuad(Xq, n, Aex, "general_rotated", nfail));
  PetscFunctionReturn(0);
}

/* Check 7: inverted (two nodes swapped) and flat elements must return PETSC_ERR_ARG_OUTOFRANGE */
static PetscErrorCode CheckInverted(PetscInt *nfail)
{
  const PetscReal Xline[12] = {0, 0, 0, 1, 0.5, 0, 2, 1, 0, 3, 1.5, 0}; /* collinear quad: no normal */
  PetscReal      X[24], Xflat[24], K[576], sig[48], u[24] = {0}, V;
  PetscErrorCode ierr;
  PetscInt       i;

  PetscFunctionBeginUser;
  for (i = 0; i < 24; i++) X[i] = Xflat[i] = distortedHex[i];
  for (i = 0; i < 3; i++) {
    X[i]     = distortedHex[3 + i];
    X[3 + i] = distortedHex[i];
  }
  for (i = 0; i < 8; i++) Xflat[3 * i + 2] = 0.25;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = Hex8Stiffness(X, 210e3, 0.3, HEX8_FULL, K);
  PetscCall(PetscPopErrorHandler());
  PetscCall(Report("inverted_error_full", (PetscReal)ierr, (PetscBool)(ierr == PETSC_ERR_ARG_OUTOFRANGE), nfail));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = Hex8Stiffness(X, 210e3, 0.3, HEX8_INCOMPATIBLE, K);
  PetscCall(PetscPopErrorHandler());
  PetscCall(Report("inverted_error_incompatible", (PetscReal)ierr, (PetscBool)(ierr == PETSC_ERR_ARG_OUTOFRANGE), nfail));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = Hex8Stress(X, u, 210e3, 0.3, HEX8_INCOMPATIBLE, sig);
  PetscCall(PetscPopErrorHandler());
  PetscCall(Report("inverted_error_stress", (PetscReal)ierr, (PetscBool)(ierr == PETSC_ERR_ARG_OUTOFRANGE), nfail));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = Hex8Stiffness(Xflat, 210e3, 0.3, HEX8_FULL, K);
  PetscCall(PetscPopErrorHandler());
  PetscCall(Report("degenerate_flat_error_full", (PetscReal)ierr, (PetscBool)(ierr == PETSC_ERR_ARG_OUTOFRANGE), nfail));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = QuadPairPenaltyStiffness(Xline, 1e3, 20, K);
  PetscCall(PetscPopErrorHandler());
  PetscCall(Report("degenerate_quad_error", (PetscReal)ierr, (PetscBool)(ierr == PETSC_ERR_ARG_OUTOFRANGE), nfail));
  /* the valid element still works after the errors */
  PetscCall(Hex8Volume(distortedHex, &V));
  PetscCall(Report("valid_after_errors_volume", V, (PetscBool)(V > 0), nfail));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscInt nfail = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(CheckStiffnessBasics(HEX8_FULL, "full", &nfail));
  PetscCall(CheckStiffnessBasics(HEX8_INCOMPATIBLE, "incompatible", &nfail));
  PetscCall(CheckMassVolume(&nfail));
  PetscCall(CheckPatch(HEX8_FULL, "full", &nfail));
  PetscCall(CheckPatch(HEX8_INCOMPATIBLE, "incompatible", &nfail));
  PetscCall(CheckBending(&nfail));
  PetscCall(CheckQuads(&nfail));
  PetscCall(CheckInverted(&nfail));
  PetscCall(PetscFinalize());
  return nfail > 0 ? 1 : 0;
}
