# Micro-geometry optimisation against the mesh-in impact force (seed 000), once per pair. No
# physics here: the rule names one package function; the settings are the config section
# "optimise". A variant {from: optimise} takes results/{study}/{pair}/optimise/pair.yaml
# (rule variant_pair), so the later stages run on the optimum like on any variant.


rule optimise:
    """GA (or NSGA-II, or random search) over seed 000's six modification parameters: every
    generation, the optimum and the random-search baseline (ga.nc), and the optimum as a pair file."""
    input:
        unpack(fe_tables("impact")),  # the optimiser runs the study's impact model
        pair=pair_file,
    output:
        nc="results/{study}/{pair}/optimise/ga.nc",
        pair="results/{study}/{pair}/optimise/pair.yaml",
    log:
        "logs/{study}/{pair}/optimise.log",
    params:
        function=versioned("gearmesh.datasets.optimise:optimise_dataset"),
        # the impact model is the study's (impact: section), so the optimum is optimal for the impact stage
        settings=lambda wildcards: {**config["optimise"], "impact": config.get("impact")},
    conda:
        ENV
    script:
        "../scripts/optimise.py"


rule plot_optimise:
    """Convergence (the run and the random search on one axis) and the optimum's modification map."""
    input:
        ga="results/{study}/{pair}/optimise/ga.nc",
    output:
        convergence=report_item("results/{study}/{pair}/optimise/plots/convergence.png", "optimise_convergence",
                                "optimisation", BY_PAIR),
        modification=report_item("results/{study}/{pair}/optimise/plots/modification.png", "optimise_modification",
                                 "optimisation", BY_PAIR),
    log:
        "logs/{study}/{pair}/plot_optimise.log",
    params:
        function=versioned("gearmesh.plots.optimise:optimise_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule plot_pareto:
    """NSGA-II runs: impact force against peak-to-peak LTE with the Pareto front."""
    input:
        ga="results/{study}/{pair}/optimise/ga.nc",
    output:
        pareto=report_item("results/{study}/{pair}/optimise/plots/pareto.png", "optimise_pareto", "optimisation",
                           BY_PAIR),
    log:
        "logs/{study}/{pair}/plot_pareto.log",
    params:
        function=versioned("gearmesh.plots.optimise:pareto_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"
