/* A vector option of a fixed number of real components (a direction, an axis), checked whole:
   PETSc's array reader fills what it is given and leaves the rest at their defaults, so that
   "-load_direction 1,0" would run along (1, 0, -1) without a word. */
#include "boltrom.h"

/* The components of text separated by commas (spaces around them allowed) into v (at most
   nmax of them kept); *count: how many there are; *bad: the first that is not a finite real,
   or -1. */
static PetscErrorCode BoltParseComponents(const char text[], PetscInt nmax, PetscReal v[], PetscInt *count, PetscInt *bad)
{
  char        buf[PETSC_MAX_PATH_LEN];
  const char *p;

  PetscFunctionBeginUser;
  *count = 0;
  *bad   = -1;
  for (p = text; *p == ' '; p++) {}
  if (!*p) PetscFunctionReturn(0);
  while (p) {
    const char *comma = strchr(p, ',');
    size_t      len   = comma ? (size_t)(comma - p) : strlen(p);
    char       *end;
    double      x;

    while (len && p[0] == ' ') {
      p++;
      len--;
    }
    while (len && p[len - 1] == ' ') len--;
    len = PetscMin(len, sizeof(buf) - 1);
    PetscCall(PetscMemcpy(buf, p, len));
    buf[len] = '\0';
    x        = len ? strtod(buf, &end) : 0;
    if (*bad < 0 && (!len || *end || PetscIsInfOrNanReal((PetscReal)x))) *bad = *count;
    if (*count < nmax) v[*count] = (PetscReal)x;
    (*count)++;
    p = comma ? comma + 1 : NULL;
  }
  PetscFunctionReturn(0);
}

/* Inside PetscOptionsBegin/End: option opt as exactly n finite reals, comma separated, into v
   (left at its defaults if the option is not given). Any other count, or a value that is not a
   finite number, is a one-line error naming the option, what was given and what is expected. */
PetscErrorCode BoltOptionsRealVector(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscInt n, PetscReal v[], PetscBool *set)
{
  char      given[PETSC_MAX_PATH_LEN] = "";
  PetscReal w[16];
  PetscInt  count = 0, bad = -1, nread = n;
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCheck(n >= 1 && n <= 16, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "A vector option of %" PetscInt_FMT " components is not supported", n);
  PetscCall(PetscOptionsGetString(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, given, sizeof(given), &has));
  if (has) {
    PetscCall(BoltParseComponents(given, 16, w, &count, &bad));
    PetscCheck(count == n, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s %s: %" PetscInt_FMT " component%s given, %" PetscInt_FMT " expected, comma-separated (%s)", opt, given[0] ? given : "(empty)", count, count == 1 ? "" : "s", n, n == 3 ? "x,y,z" : "c1,c2,...");
    PetscCheck(bad < 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s %s: component %" PetscInt_FMT " is not a finite number; give %" PetscInt_FMT " finite reals, comma-separated", opt, given, bad + 1, n);
  }
  /* -help lists the default whole (PETSc's array reader prints its first component only) */
  if (PetscOptionsObject->printhelp && PetscOptionsObject->count == 1 && !PetscOptionsObject->alreadyprinted) {
    PetscCall((*PetscHelpPrintf)(PetscOptionsObject->comm, "  -%s%s <%g", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1, (double)v[0]));
    for (PetscInt i = 1; i < n; i++) PetscCall((*PetscHelpPrintf)(PetscOptionsObject->comm, ",%g", (double)v[i]));
    PetscCall((*PetscHelpPrintf)(PetscOptionsObject->comm, ">: %s\n", text));
  }
  PetscCall(PetscOptionsGetRealArray(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, v, &nread, set));
  PetscFunctionReturn(0);
}

/* Whether token (spaces around it allowed) reads whole as a number that is not finite: "nan",
   "inf", "-Infinity", or one too large for a real ("1e999"). A word that is not a number is not. */
static PetscBool BoltTokenNonFinite(const char *p, size_t len)
{
  char   buf[64], *end;
  double x;

  while (len && *p == ' ') p++, len--;
  while (len && p[len - 1] == ' ') len--;
  if (!len || len >= sizeof(buf)) return PETSC_FALSE;
  memcpy(buf, p, len);
  buf[len] = '\0';
  x        = strtod(buf, &end);
  return (PetscBool)(!*end && !isfinite(x));
}

/* Every real option is refused a value that is not finite, whoever reads it: PETSc's reader takes
   "nan" and "inf" as numbers, which then pass range checks (every comparison with a NaN is false)
   or overflow a conversion. Called before any option is read, so that every option given is still
   in the unused list; a comma-separated value is checked component by component. */
PetscErrorCode BoltOptionsCheckFinite(MPI_Comm comm)
{
  PetscInt n;
  char   **names, **values;
  char     msg[PETSC_MAX_PATH_LEN] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n && !msg[0]; i++) {
    const char *p = values[i];
    PetscInt    k = 0, ncomma = 0;
    if (!p) continue;
    for (const char *c = p; *c; c++) ncomma += (*c == ',');
    while (p && !msg[0]) {
      const char *comma = strchr(p, ',');
      size_t      len   = comma ? (size_t)(comma - p) : strlen(p);
      k++;
      if (BoltTokenNonFinite(p, len)) {
        if (ncomma) PetscCall(PetscSNPrintf(msg, sizeof(msg), "-%s %s: component %" PetscInt_FMT " is not a finite number; give finite reals, comma-separated", names[i], values[i], k));
        else PetscCall(PetscSNPrintf(msg, sizeof(msg), "-%s %s: not a finite number; give a finite real value", names[i], values[i]));
      }
      p = comma ? comma + 1 : NULL;
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(!msg[0], comm, PETSC_ERR_USER_INPUT, "%s", msg);
  PetscFunctionReturn(0);
}
