# One make rule per asset: every .gltf and .glb under IN baked into OUT as .glb, with its report
# beside it. Each rule is a process of its own that reads only its asset and writes only its
# outputs, so `make -j` spreads a folder over the cores, and a build system or render-farm queue
# that runs rules on several machines spreads it over those: raps-gltf writes the same bytes for
# the same input and flags on any machine and thread count (docs/reproducibility.md).
#
#   make -f per-asset.mk -j8 IN=assets OUT=baked [RAPS_GLTF=raps-gltf] [FLAGS="--group scene"]
#
# An asset's output is rebuilt when the asset is newer. Paths with spaces are not supported (make).
IN ?= assets
OUT ?= baked
RAPS_GLTF ?= raps-gltf
FLAGS ?=

SOURCES := $(shell find $(IN) -name '*.gltf' -o -name '*.glb')
TARGETS := $(patsubst $(IN)/%,$(OUT)/%.glb,$(basename $(SOURCES)))

all: $(TARGETS)

define bake
	@mkdir -p $(@D)
	$(RAPS_GLTF) $< $@ --overwrite --no-progress --report $(basename $@).json $(FLAGS)
endef

$(OUT)/%.glb: $(IN)/%.gltf
	$(bake)

$(OUT)/%.glb: $(IN)/%.glb
	$(bake)

.PHONY: all
