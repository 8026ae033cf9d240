# Micro-geometry optimisations against the mesh-in impact (seed 000), each named in the config
# section "optimise" ({run}), once per pair. No physics here: the rule names one package
# function; the settings are the run's section, the study's impact model and its tolerances. A
# variant {from: optimise.NAME} takes results/{study}/{pair}/optimise/NAME/pair.yaml as its pair
# file (common.smk variant_source_pair), so the later stages run on the optimum like on any variant.


rule optimise:
    """GA (or NSGA-II, or random search) over seed 000's six modification parameters: every
    generation, the optimum with its load window and tolerance spread (ga.nc), the optimum as a
    pair file; figures: convergence (and the random search on one axis when it ran) and the optimum's
    modification map."""
    input:
        unpack(stage_inputs("optimise")),
    output:
        nc=stage_output("optimise"),
        pair="results/{study}/{pair}/optimise/{run}/pair.yaml",
        convergence=report_item("results/{study}/{pair}/optimise/{run}/plots/convergence.png",
                                "optimise_convergence", "Optimisation", BY_RUN),
        modification=report_item("results/{study}/{pair}/optimise/{run}/plots/modification.png",
                                 "optimise_modification", "Optimisation", BY_RUN),
    log:
        "logs/{study}/{pair}/optimise/{run}.log",
    # the longest job, and the variants it writes wait for it: start it first
    priority: 10
    params:
        **stage_params("optimise"),
    conda:
        ENV
    script:
        "../scripts/optimise.py"


rule plot_pareto:
    """NSGA-II runs: impact force against peak-to-peak LTE with the Pareto front (its own job: only a
    run with method nsga2 has one, and an output cannot depend on a wildcard's config)."""
    localrule: True  # a study table or figure: on a cluster, run where Snakemake runs (SLURM profile)
    input:
        ga=stage_output("optimise"),
    output:
        pareto=report_item("results/{study}/{pair}/optimise/{run}/plots/pareto.png", "optimise_pareto",
                           "Optimisation", BY_RUN),
    log:
        "logs/{study}/{pair}/optimise/pareto_{run}.log",
    params:
        function=versioned_param("gearmesh.plots.optimise:pareto_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"
