"""Table II of Pannetier, Dezert and Sella (FUSION 2014): the paper's per-target RSE and TLR of its
two algorithms, which the ONERA table prints and draws beside ours."""

# Table II of Benjamin Pannetier, Jean Dezert and Genevieve Sella, "Multiple target tracking with
# wireless sensor network for ground battlefield surveillance", Proceedings of the 17th International
# Conference on Information Fusion (FUSION 2014), Salamanca, Spain, July 2014 (hal-01070361), §V:
# per target (1-20), (RSE in metres, TLR) of algorithm 1 (with roads) and of algorithm 2 (without).
PAPER_A1 = [(10.48, 0.99), (7.43, 1.0), (5.32, 1.0), (6.20, 0.88), (6.35, 1.0),
            (5.66, 0.68), (22.45, 0.60), (3.43, 1.0), (7.07, 0.86), (12.79, 0.63),
            (6.72, 0.82), (6.58, 0.81), (8.56, 0.51), (1.91, 1.0), (10.39, 0.37),
            (12.77, 0.34), (6.44, 0.78), (9.30, 0.48), (7.06, 0.60), (18.55, 0.38)]
PAPER_A2 = [(19.43, 0.80), (7.70, 1.0), (12.00, 1.0), (6.08, 0.90), (11.74, 0.59),
            (5.20, 0.68), (16.11, 0.85), (7.42, 0.90), (10.28, 0.50), (12.52, 0.45),
            (8.42, 0.85), (7.71, 0.89), (9.87, 0.61), (4.19, 1.0), (9.02, 0.51),
            (12.67, 0.31), (9.33, 0.51), (8.87, 0.46), (7.56, 0.44), (13.40, 0.88)]

PAPER_TARGETS = len(PAPER_A1)
