"""Layer 6, studies: many arches, many motions, and the answers built from them.

Ensembles (:mod:`.ensemble`), collapse curves (:mod:`.curves`), IDA and stripes (:mod:`.ida`),
fragility (:mod:`.fragility`), Sobol indices (:mod:`.sensitivity`), defect maps
(:mod:`.defectmap`), the code check (:mod:`.codecheck`), the contact engine against the four-link
model (:mod:`.verification`), the assessment (:mod:`.assessment`), the paper's study
(:mod:`.paper`), the work estimate (:mod:`.work`) and the runner of a study's rounds
(:mod:`.runner`).  Nothing here draws or prints: figures and text are the reports' (layer 7).
"""
