#ifndef BOLTROM_H
#define BOLTROM_H
/* boltrom: vibration of bolted joints with contact, full and reduced order models.
   One struct per concept, each with a Create / SetFromOptions / SetUp / View / Destroy cycle. */
#include <petscdmplex.h>
#include <petscksp.h>
#include <slepceps.h>
#include <petscsf.h>
#include <petscbt.h>
#include "boltrom_element.h"

#define BOLTROM_MAX_PARTS 32
#define BOLTROM_MAX_PAIRS 32
#define BOLTROM_MAX_BOLTS 16
#define BOLTROM_NAME_LEN  128

/* sys/json.c: the run summary's writer, which every module may write its keys to */
typedef struct _n_BoltJSON BoltJSON;

/* One header per module, in the order of the layers: each may use those before it */
#include "boltrom/sys.h"
#include "boltrom/model.h"
#include "boltrom/contact.h"
#include "boltrom/solve.h"
#include "boltrom/rom.h"
#include "boltrom/app.h"

#endif
