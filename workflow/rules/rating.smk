# Load capacity of one micro-geometry variant of a pair at the LTCA's torques (ISO 6336-2/-3 method B
# with the LTCA's stresses and load factors), and the variants side by side. No physics here.


rule rating:
    """S_H, S_F, stresses and load factors (standard and LTCA) at every LTCA torque (rating.nc); figures: the
    contact-pressure map over the pinion flank, the tooth-root stress along the face."""
    input:
        unpack(stage_inputs("rating")),
    output:
        nc=stage_output("rating"),
        pressure_map=report_item("results/{study}/{pair}/{variant}/plots/pressure_map.png", "pressure_map",
                                 "Load capacity", BY_VARIANT),
        root_stress_face=report_item("results/{study}/{pair}/{variant}/plots/root_stress_face.png",
                                     "root_stress_face", "Load capacity", BY_VARIANT),
    log:
        "logs/{study}/{pair}/{variant}/rating.log",
    priority: 4  # after its variant's LTCA, before the study tables (rule dynamics)
    params:
        **stage_params("rating"),
    conda:
        ENV
    script:
        "../scripts/pair_stage.py"


rule load_capacity_table:
    """S_H, S_F, peak contact pressure (flank or edge) and peak root stress of every variant and torque."""
    localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
    input:
        rating=every_variant("rating"),
    output:
        nc="results/{study}/{pair}/load_capacity_table.nc",
        csv=report_item("results/{study}/{pair}/load_capacity_table.csv", "load_capacity_table", "Load capacity",
                        BY_PAIR),
    log:
        "logs/{study}/{pair}/load_capacity_table.log",
    params:
        function=versioned_param("gearmesh.datasets.rating:load_capacity_table_dataset"),
    conda:
        ENV
    script:
        "../scripts/collect.py"
