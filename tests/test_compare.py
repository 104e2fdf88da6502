

def test_reference_with_a_gap_and_another_length_still_finds_the_push() -> None:
    gapped = _run(1, cycles=3.0)
    gapped.data.iloc[250:300] = np.nan  # values missing: a gap, as a reader leaves it
    refs = [gapped, _run(2, start=0.8, cycles=4.5)]
    c = compare_runs(_run(3, start=1.3, cycles=5.0, push=(5.0, 5.6, 1, 1.5)), refs,
                     networks=False)
    assert c.compared > 0.95
    assert [(i.start < 5.6 and i.stop > 5.0) for i in c.intervals] == [True]
